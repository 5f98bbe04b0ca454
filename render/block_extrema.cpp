#include "render/block_extrema.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vr {
namespace {

// The float at or below (at or above) x.
float floatBelow(double x) {
    const float f = float(x);
    return double(f) <= x ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float floatAbove(double x) {
    const float f = float(x);
    return double(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

int blocksAlong(int voxels, int level) {
    const int size = device::kBlockSize << level;
    return (voxels + size - 1) / size;
}

}  // namespace

std::size_t BlockExtrema::texel(int level, const Vec3i& v) const {
    const int size = device::kBlockSize << level;
    return (std::size_t(levelZ[level] + v.z / size) * imageDims.y + std::size_t(v.y / size)) * imageDims.x +
           std::size_t(v.x / size);
}

BlockExtrema blockExtrema(const Volume& scalars) {
    const Vec3i dims = scalars.grid.dims;
    BlockExtrema e;
    e.imageDims = {blocksAlong(dims.x, 0), blocksAlong(dims.y, 0), 0};
    for (int level = 0; level < device::kBlockLevels; ++level) {
        e.levelZ[level] = e.imageDims.z;
        e.imageDims.z += blocksAlong(dims.z, level);
    }
    e.range.assign(2 * std::size_t(e.imageDims.x) * e.imageDims.y * e.imageDims.z, 0.0f);
    auto at = [&](int level, const Vec3i& b) {  // texel index of block b of a level
        return (std::size_t(e.levelZ[level] + b.z) * e.imageDims.y + b.y) * e.imageDims.x + b.x;
    };
    const bool widen = scalars.sourceType == ScalarType::Float32;
    constexpr int kBlock = device::kBlockSize;
    tbb::parallel_for(0, blocksAlong(dims.z, 0), [&](int bz) {
        for (int by = 0; by < e.imageDims.y; ++by)
            for (int bx = 0; bx < e.imageDims.x; ++bx) {
                const Vec3i b{bx, by, bz};
                Vec3i first, last;  // the block grown by one voxel, within the volume
                for (int a = 0; a < 3; ++a) {
                    first[a] = std::max(0, b[a] * kBlock - 1);
                    last[a] = std::min(dims[a] - 1, (b[a] + 1) * kBlock);
                }
                float lo = std::numeric_limits<float>::infinity(), hi = -lo;
                for (int z = first.z; z <= last.z; ++z)
                    for (int y = first.y; y <= last.y; ++y) {
                        const float* row = scalars.values.data() + linearIndex(dims, first.x, y, z);
                        const auto [rowLo, rowHi] = std::minmax_element(row, row + (last.x - first.x + 1));
                        lo = std::min(lo, *rowLo);
                        hi = std::max(hi, *rowHi);
                    }
                const double slack =
                    widen && lo != hi ? std::ldexp(std::max(std::abs(double(lo)), std::abs(double(hi))), -20) : 0;
                e.range[2 * at(0, b)] = floatBelow(double(lo) - slack);
                e.range[2 * at(0, b) + 1] = floatAbove(double(hi) + slack);
            }
    });
    for (int level = 1; level < device::kBlockLevels; ++level)
        for (int bz = 0; bz < blocksAlong(dims.z, level); ++bz)
            for (int by = 0; by < blocksAlong(dims.y, level); ++by)
                for (int bx = 0; bx < blocksAlong(dims.x, level); ++bx) {
                    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
                    for (int c = 0; c < 8; ++c) {
                        const Vec3i child{2 * bx + (c & 1), 2 * by + (c >> 1 & 1), 2 * bz + (c >> 2 & 1)};
                        if (child.x >= blocksAlong(dims.x, level - 1) || child.y >= blocksAlong(dims.y, level - 1) ||
                            child.z >= blocksAlong(dims.z, level - 1))
                            continue;
                        lo = std::min(lo, e.range[2 * at(level - 1, child)]);
                        hi = std::max(hi, e.range[2 * at(level - 1, child) + 1]);
                    }
                    e.range[2 * at(level, {bx, by, bz})] = lo;
                    e.range[2 * at(level, {bx, by, bz}) + 1] = hi;
                }
    return e;
}

}  // namespace vr
