// The scalars that trilinear sampling reads in each voxel (docs/ALGORITHMS.md section 9).
#pragma once
#include <vector>

#include "core/vec3.h"

namespace vr {

struct ScalarRange {
    float lo, hi;
};

// Per voxel, the smallest and largest scalar of its interpolation footprint: the 2x2x2 cells around every point of
// the voxel's cell, together its 3x3x3 neighbourhood, clamped at the volume's edge (cell-centred sampling).
std::vector<ScalarRange> footprintRanges(const Vec3i& dims, const std::vector<float>& scalars);

}  // namespace vr
