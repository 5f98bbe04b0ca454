// Regions for post-classified trilinear sampling (docs/ALGORITHMS.md section 9).
#pragma once
#include <vector>

#include <cstdint>
#include <limits>

#include "core/progress.h"
#include "core/regions.h"
#include "preprocess/segment/classified_voxels.h"
#include "preprocess/segment/footprint_ranges.h"

namespace vr {

// A cell's label before growth: one that may join a region, and one that joins none (a border voxel, a mixed block).
constexpr uint32_t kUnsetCell = std::numeric_limits<uint32_t>::max();
constexpr uint32_t kBorderCell = kUnsetCell - 1;

// Grows regions over a grid of `dims` cells from seeds in cell order, 6-connected, each keeping the entry range
// spanned by its cells' `ranges` `spread`-alike within `threshold`. `label` holds kBorderCell where a cell is a region
// of its own and kUnsetCell elsewhere; on return the labels 0..count-1 in first-cell order. Returns the count.
// `progress` hears the share of seeds passed.
uint32_t growRegions(const Vec3i& dims, const std::vector<EntryRange>& ranges, const ClassificationSpread& spread,
                     double threshold, std::vector<uint32_t>& label, const Progress& progress = {});

// Regions grown from seeds in voxel order, 6-connected, each keeping the scalar interval [min, max] that its voxels'
// interpolation footprints span (footprint_ranges.h) `spread`-alike within T_o, and its normals alike as the region
// key has them. A voxel whose footprint alone is not alike, or (normals in use) whose 26 neighbours are not all
// alike in normals to it, is a border voxel: a region of its own. Labels 0..count-1 in first-voxel order.
// `scalars` are the values behind `voxels`.
void growPostClassifiedRegions(const ClassifiedVoxels& voxels, const SegmentationParams& params,
                               const std::vector<float>& scalars, const ClassificationSpread& spread, Regions& regions,
                               const Progress& progress = {});

}  // namespace vr
