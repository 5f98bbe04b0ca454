// The scalar range of each block of the volume over the block's voxels and the trilinear footprints of its samples,
// so that any sample whose voxel lies in the block, nearest or trilinear, takes a value in the range: at one block
// edge (what the hier field classifies, preprocess/pipeline/hier_field.h) or at every level of shaders/blend.h
// (edges of 4, 8, 16 and 32 voxels), what the blocks caster leaps by (docs/ALGORITHMS.md section 11). Built from the
// scalars at render time (the CPU reference) or upload (the device); 8 bytes per 64 voxels and a seventh more for
// the coarser levels.
#pragma once
#include <array>
#include <vector>

#include "core/vec3.h"
#include "core/volume.h"
#include "shaders/blend.h"

namespace vr {

// The levels stacked along z in one image, as the device reads them (one RG32F texel per block: lo, hi):
// level j's block b at (b.x, b.y, levelZ[j] + b.z) in blocks.
struct BlockExtrema {
    Vec3i imageDims;
    std::array<int, device::kBlockLevels> levelZ{};
    std::vector<float> range;  // lo, hi per texel, x fastest (texels beyond a coarse level's blocks are unused)

    float lo(int level, const Vec3i& voxel) const { return range[2 * texel(level, voxel)]; }
    float hi(int level, const Vec3i& voxel) const { return range[2 * texel(level, voxel) + 1]; }

    // The texel of the level's block that holds the voxel.
    std::size_t texel(int level, const Vec3i& voxel) const;
};

// One level: blocks of 2^blockShift voxels per axis (the last of an axis cut short by the border).
struct BlockRanges {
    Vec3i blocks;
    std::vector<float> range;  // lo, hi per block, x fastest
};

// Each block's range over its voxels and one voxel around it (a trilinear sample in a voxel reads its neighbours),
// within the volume. For float scalars the range is widened by 2^-20 of its largest magnitude: a float blend of a
// footprint's corners may round a little past them (integer scalars' blends stay within them exactly; a blend of
// equal corners is exact, so a block of one value keeps it: average leaps over it). blockShift >= 1.
BlockRanges blockRanges(const Volume& scalars, int blockShift);

// Each finest block's range as blockRanges gives it, each coarser block's over its 8 children.
BlockExtrema blockExtrema(const Volume& scalars);

}  // namespace vr
