// The regions of the hierarchical EACD's coarse level (docs/ALGORITHMS.md section 10): blocks of voxels, each
// homogeneous or mixed, grown into regions as voxels are (grown_regions.h), from one scalar range per block.
#pragma once
#include <cstdint>
#include <vector>

#include "core/regions.h"
#include "preprocess/segment/footprint_ranges.h"

namespace vr {

struct BlockRegions {
    Regions regions;                   // over the grid of blocks; a mixed block is a region of its own
    std::vector<uint8_t> homogeneous;  // per block: 1 where its samples may be leapt over
};

// `ranges`: per block of a grid of `blocks` (x fastest), the table entries that classify every scalar its samples
// can take (its voxels and their trilinear footprints). A block is homogeneous when that range is alike within T_o
// (`spread`) and, with normals in use, transparent: the shade of a span is its first sample's, and only a
// transparent span shows none. Homogeneous blocks grow into regions whose joint range stays alike. Throws
// InputError for a negative or NaN threshold.
BlockRegions segmentBlocks(const Vec3i& blocks, const std::vector<EntryRange>& ranges,
                           const ClassificationSpread& spread, const SegmentationParams& params);

}  // namespace vr
