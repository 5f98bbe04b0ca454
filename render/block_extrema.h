// The scalar range of each block of kBlockSize^3 voxels (shaders/blend.h), what the blocks caster leaps by
// (docs/ALGORITHMS.md section 11): over the block's voxels and the trilinear footprints of its samples, so that any
// sample whose voxel lies in the block, nearest or trilinear, takes a value in the range. Built from the scalars at
// render time (the CPU reference) or upload (the device); an eighth of a percent of the scalars' size.
#pragma once
#include <vector>

#include "core/vec3.h"
#include "core/volume.h"

namespace vr {

struct BlockExtrema {
    Vec3i blocks;              // per axis ceil(N / kBlockSize)
    std::vector<float> range;  // lo, hi per block, x fastest: the device's RG32F texels

    float lo(const Vec3i& voxel) const { return range[2 * index(voxel)]; }
    float hi(const Vec3i& voxel) const { return range[2 * index(voxel) + 1]; }

private:
    std::size_t index(const Vec3i& voxel) const;
};

// Each block's range over its voxels and one voxel around it (a trilinear sample in a voxel reads its neighbours).
// For float scalars the range is widened by 2^-20 of its largest magnitude: a float blend of a footprint's corners
// may round a little past them (integer scalars' blends stay within them exactly; a blend of equal corners is
// exact, so a block of one value keeps it: average leaps over it).
BlockExtrema blockExtrema(const Volume& scalars);

}  // namespace vr
