#include "render/block_extrema.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "shaders/blend.h"

namespace vr {
namespace {

constexpr int kBlock = device::kBlockSize;

// The float at or below (at or above) x.
float floatBelow(double x) {
    const float f = float(x);
    return double(f) <= x ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}
float floatAbove(double x) {
    const float f = float(x);
    return double(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

}  // namespace

std::size_t BlockExtrema::index(const Vec3i& v) const {
    return (std::size_t(v.z / kBlock) * blocks.y + std::size_t(v.y / kBlock)) * blocks.x + std::size_t(v.x / kBlock);
}

BlockExtrema blockExtrema(const Volume& scalars) {
    const Vec3i dims = scalars.grid.dims;
    BlockExtrema e;
    e.blocks = {(dims.x + kBlock - 1) / kBlock, (dims.y + kBlock - 1) / kBlock, (dims.z + kBlock - 1) / kBlock};
    e.range.resize(2 * std::size_t(e.blocks.x) * e.blocks.y * e.blocks.z);
    const bool widen = scalars.sourceType == ScalarType::Float32;
    tbb::parallel_for(0, e.blocks.z, [&](int bz) {
        for (int by = 0; by < e.blocks.y; ++by)
            for (int bx = 0; bx < e.blocks.x; ++bx) {
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
                const double slack = widen && lo != hi ? std::ldexp(std::max(std::abs(double(lo)), std::abs(double(hi))), -20) : 0;
                const std::size_t i = (std::size_t(bz) * e.blocks.y + by) * e.blocks.x + bx;
                e.range[2 * i] = floatBelow(double(lo) - slack);
                e.range[2 * i + 1] = floatAbove(double(hi) + slack);
            }
    });
    return e;
}

}  // namespace vr
