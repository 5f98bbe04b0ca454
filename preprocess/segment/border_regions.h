// Regions for trilinear sampling (docs/ALGORITHMS.md section 3, thesis 4.3.2).
#pragma once
#include "core/regions.h"

namespace vr {

// Every voxel with one of its 26 neighbours in another region (its 2x2x2 interpolation footprint mixes regions)
// becomes a region of its own, so a leap never starts where interpolation mixes regions. Labels stay compact
// and ordered by first voxel.
void splitBorderVoxels(Regions& regions);

}  // namespace vr
