// Each block's scalar range (render/block_extrema.h): over its voxels and one voxel around it, at one block edge
// (what the hier field classifies) and at every level of the blocks caster, which coarsens the finest.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "datasets/phantoms.h"
#include "render/block_extrema.h"

namespace vr {
namespace {

// The range of the voxels of block b (edge 2^shift) and one voxel around it, voxel by voxel.
std::pair<float, float> rangeByVoxels(const Volume& v, int shift, const Vec3i& b) {
    const int edge = 1 << shift;
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int z = std::max(0, b.z * edge - 1); z <= std::min(v.grid.dims.z - 1, (b.z + 1) * edge); ++z)
        for (int y = std::max(0, b.y * edge - 1); y <= std::min(v.grid.dims.y - 1, (b.y + 1) * edge); ++y)
            for (int x = std::max(0, b.x * edge - 1); x <= std::min(v.grid.dims.x - 1, (b.x + 1) * edge); ++x) {
                lo = std::min(lo, v.at(x, y, z));
                hi = std::max(hi, v.at(x, y, z));
            }
    return {lo, hi};
}

TEST(RenderBlockExtrema, EachBlockSpansItsVoxelsAndOneAround) {
    // Dimensions no edge divides: the last block of each axis is cut short by the border.
    const Volume v = noisePhantom({37, 22, 13}, 5);
    for (int shift : {1, 2, 3}) {
        const BlockRanges r = blockRanges(v, shift);
        const int edge = 1 << shift;
        ASSERT_EQ(r.blocks, (Vec3i{(37 + edge - 1) / edge, (22 + edge - 1) / edge, (13 + edge - 1) / edge}));
        ASSERT_EQ(r.range.size(), 2 * voxelCount(r.blocks));
        std::size_t i = 0;
        for (int z = 0; z < r.blocks.z; ++z)
            for (int y = 0; y < r.blocks.y; ++y)
                for (int x = 0; x < r.blocks.x; ++x, ++i) {
                    const auto [lo, hi] = rangeByVoxels(v, shift, {x, y, z});
                    EXPECT_EQ(r.range[2 * i], lo) << shift << ": block " << x << " " << y << " " << z;
                    EXPECT_EQ(r.range[2 * i + 1], hi) << shift << ": block " << x << " " << y << " " << z;
                }
    }
}

TEST(RenderBlockExtrema, EveryLevelOfTheBlocksCasterIsItsEdgesRange) {
    // Integer scalars: a coarse block's range over its children is its range over its own voxels and one around.
    const Volume v = noisePhantom({70, 45, 33}, 9);
    const BlockExtrema e = blockExtrema(v);
    for (int level = 0; level < device::kBlockLevels; ++level) {
        const BlockRanges r = blockRanges(v, device::kBlockShift + level);
        const int edge = device::kBlockSize << level;
        std::size_t i = 0;
        for (int z = 0; z < r.blocks.z; ++z)
            for (int y = 0; y < r.blocks.y; ++y)
                for (int x = 0; x < r.blocks.x; ++x, ++i) {
                    const Vec3i corner{x * edge, y * edge, z * edge};
                    EXPECT_EQ(e.lo(level, corner), r.range[2 * i]) << level;
                    EXPECT_EQ(e.hi(level, corner), r.range[2 * i + 1]) << level;
                }
    }
}

TEST(RenderBlockExtrema, FloatRangesAreWidenedUnlessOneValue) {
    Volume v = noisePhantom({9, 9, 9}, 3, 100, 200);
    v.sourceType = ScalarType::Float32;
    std::fill(v.values.begin(), v.values.begin() + 9 * 9 * 4, 50.0f);  // slices 0..3: block z 0 of one value
    const BlockRanges r = blockRanges(v, 1);
    EXPECT_EQ(r.range[0], 50.0f);  // block (0, 0, 0): slices 0..2, all 50
    EXPECT_EQ(r.range[1], 50.0f);
    const std::size_t last = voxelCount(r.blocks) - 1;
    const auto [lo, hi] = rangeByVoxels(v, 1, r.blocks - Vec3i{1, 1, 1});
    EXPECT_LT(r.range[2 * last], lo);
    EXPECT_GT(r.range[2 * last + 1], hi);
    EXPECT_GE(r.range[2 * last], lo - hi * 0x1p-19f);
    EXPECT_LE(r.range[2 * last + 1], hi + hi * 0x1p-19f);
}

}  // namespace
}  // namespace vr
