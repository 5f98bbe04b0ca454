// The hierarchical EACD's coarse level (docs/ALGORITHMS.md section 10): the EACD builder run over a grid of blocks.
#pragma once
#include <cstdint>
#include <vector>

#include "core/distance_fields.h"
#include "core/regions.h"

namespace vr {

// The EACD of `blockRegions` (a grid of blocks of 2^blockShift voxels per axis, each mixed block a region of its
// own) in the octants of the mask, written in log16, in block units: per block its box in blocks with
// kHomogeneousBlockBit set where `homogeneous`, 0 where mixed.
BlockEACD buildBlockEACD(const Regions& blockRegions, const std::vector<uint8_t>& homogeneous, int blockShift,
                         unsigned octants = kAllOctants);

}  // namespace vr
