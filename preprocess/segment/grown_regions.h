// Regions for post-classified trilinear sampling (docs/ALGORITHMS.md section 9).
#pragma once
#include <vector>

#include "core/regions.h"
#include "preprocess/segment/classified_voxels.h"

namespace vr {

// Regions grown from seeds in voxel order, 6-connected, each keeping the scalar interval [min, max] that its voxels'
// interpolation footprints span (footprint_ranges.h) `spread`-alike within T_o, and its normals alike as the region
// key has them. A voxel whose footprint alone is not alike, or (normals in use) whose 26 neighbours are not all
// alike in normals to it, is a border voxel: a region of its own. Labels 0..count-1 in first-voxel order.
// `scalars` are the values behind `voxels`.
void growPostClassifiedRegions(const ClassifiedVoxels& voxels, const SegmentationParams& params,
                               const std::vector<float>& scalars, const ClassificationSpread& spread, Regions& regions);

}  // namespace vr
