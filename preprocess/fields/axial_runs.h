// Axial run lengths, the building block of EACD (ALGORITHMS.md section 4).
#pragma once
#include <cstdint>
#include <vector>

#include "core/regions.h"

namespace vr {

// run[u] = number of voxels of u's region met from u stepping by `sign` along `axis`, u included, stopping at the
// volume border. Cap: runs above kDistanceCap (255) are stored as 255 (a shorter run is still homogeneous).
std::vector<uint8_t> axialRuns(const Regions& regions, int axis, int sign);

}  // namespace vr
