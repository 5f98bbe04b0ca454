#include "render/block_extrema.h"

#include <tbb/blocked_range.h>
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

// lo = min(lo, fromLo) and hi = max(hi, fromHi) element by element (a run of voxels folds in as both).
void fold(const float* fromLo, const float* fromHi, std::size_t n, float* lo, float* hi) {
    for (std::size_t i = 0; i < n; ++i) {
        lo[i] = std::min(lo[i], fromLo[i]);
        hi[i] = std::max(hi[i], fromHi[i]);
    }
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

BlockRanges blockRanges(const Volume& scalars, int blockShift) {
    const Vec3i dims = scalars.grid.dims;
    const int edge = 1 << blockShift;
    auto along = [&](int voxels) { return (voxels + edge - 1) >> blockShift; };
    BlockRanges r{{along(dims.x), along(dims.y), along(dims.z)}, {}};
    r.range.resize(2 * voxelCount(r.blocks));
    // The voxels of block b along an axis and one each side, within the volume.
    auto span = [&](int b, int voxels) {
        return std::pair{std::max(0, b * edge - 1), std::min(voxels - 1, (b + 1) * edge)};
    };
    const bool widen = scalars.sourceType == ScalarType::Float32;
    const std::vector<float>& values = floatValues(scalars);
    const std::size_t sliceVoxels = std::size_t(dims.x) * dims.y;
    // A slab of blocks at a time: its slices folded voxel by voxel into one (whole rows, which vectorise), that
    // slice's rows folded per row of blocks, then each block's run of the folded row.
    tbb::parallel_for(tbb::blocked_range<int>(0, r.blocks.z), [&](const tbb::blocked_range<int>& slabs) {
        std::vector<float> sliceLo(sliceVoxels), sliceHi(sliceVoxels), rowLo(std::size_t(dims.x)),
            rowHi(std::size_t(dims.x));
        for (int bz = slabs.begin(); bz < slabs.end(); ++bz) {
            const auto [z0, z1] = span(bz, dims.z);
            const float* first = values.data() + std::size_t(z0) * sliceVoxels;
            std::copy(first, first + sliceVoxels, sliceLo.begin());
            std::copy(first, first + sliceVoxels, sliceHi.begin());
            for (int z = z0 + 1; z <= z1; ++z) {
                const float* slice = values.data() + std::size_t(z) * sliceVoxels;
                fold(slice, slice, sliceVoxels, sliceLo.data(), sliceHi.data());
            }
            for (int by = 0; by < r.blocks.y; ++by) {
                const auto [y0, y1] = span(by, dims.y);
                std::copy_n(sliceLo.begin() + std::ptrdiff_t(y0) * dims.x, dims.x, rowLo.begin());
                std::copy_n(sliceHi.begin() + std::ptrdiff_t(y0) * dims.x, dims.x, rowHi.begin());
                for (int y = y0 + 1; y <= y1; ++y) {
                    const std::size_t row = std::size_t(y) * std::size_t(dims.x);
                    fold(sliceLo.data() + row, sliceHi.data() + row, std::size_t(dims.x), rowLo.data(), rowHi.data());
                }
                float* out = r.range.data() + 2 * (std::size_t(bz) * r.blocks.y + std::size_t(by)) * r.blocks.x;
                for (int bx = 0; bx < r.blocks.x; ++bx) {
                    const auto [x0, x1] = span(bx, dims.x);
                    const float lo = *std::min_element(rowLo.begin() + x0, rowLo.begin() + x1 + 1);
                    const float hi = *std::max_element(rowHi.begin() + x0, rowHi.begin() + x1 + 1);
                    const double slack =
                        widen && lo != hi ? std::ldexp(std::max(std::abs(double(lo)), std::abs(double(hi))), -20) : 0;
                    out[2 * bx] = floatBelow(double(lo) - slack);
                    out[2 * bx + 1] = floatAbove(double(hi) + slack);
                }
            }
        }
    });
    return r;
}

BlockExtrema blockExtrema(const Volume& scalars) {
    const Vec3i dims = scalars.grid.dims;
    BlockExtrema e;
    e.imageDims = {blocksAlong(dims.x, 0), blocksAlong(dims.y, 0), 0};
    for (int level = 0; level < device::kBlockLevels; ++level) {
        e.levelZ[level] = e.imageDims.z;
        e.imageDims.z += blocksAlong(dims.z, level);
    }
    // The finest level is the image's first slices, laid out as blockRanges lays its blocks out.
    e.range = blockRanges(scalars, device::kBlockShift).range;
    e.range.resize(2 * std::size_t(e.imageDims.x) * e.imageDims.y * e.imageDims.z, 0.0f);
    auto at = [&](int level, const Vec3i& b) {  // texel index of block b of a level
        return (std::size_t(e.levelZ[level] + b.z) * e.imageDims.y + b.y) * e.imageDims.x + b.x;
    };
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
