#include "preprocess/segment/footprint_ranges.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace vr {
namespace {

// Extremes over the 3x3 square of each voxel of slice z (x then y, separable) into lo and hi at the same indices.
void squareRanges(const Vec3i& d, int z, const std::vector<float>& s, FootprintRanges& out, std::vector<float>& rowLo,
                  std::vector<float>& rowHi) {
    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y), base = linearIndex(d, 0, 0, z);
    for (std::size_t row = 0; row < slice; row += nx)
        for (std::size_t x = 0; x < nx; ++x) {
            const std::size_t j = row + x, i = base + j;
            const float left = s[x == 0 ? i : i - 1], right = s[x + 1 == nx ? i : i + 1];
            rowLo[j] = std::min({left, s[i], right});
            rowHi[j] = std::max({left, s[i], right});
        }
    for (std::size_t j = 0; j < slice; ++j) {
        const std::size_t up = j < nx ? j : j - nx, down = j + nx >= slice ? j : j + nx;
        out.lo[base + j] = std::min({rowLo[up], rowLo[j], rowLo[down]});
        out.hi[base + j] = std::max({rowHi[up], rowHi[j], rowHi[down]});
    }
}

// Each voxel's square extremes widened by the squares beside it along z, in place: a column block at a time,
// keeping the block's square extremes of the slice below before they are overwritten.
void acrossSlices(const Vec3i& d, FootprintRanges& r) {
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slice, 4096), [&](const tbb::blocked_range<std::size_t>& js) {
        const std::size_t n = js.size();
        std::vector<float> belowLo(n), belowHi(n);
        for (int z = 0; z < d.z; ++z) {
            const std::size_t base = linearIndex(d, 0, 0, z) + js.begin();
            const bool hasAbove = z + 1 < d.z;
            for (std::size_t k = 0; k < n; ++k) {
                const std::size_t i = base + k;
                const float lo = r.lo[i], hi = r.hi[i];
                float wideLo = lo, wideHi = hi;
                if (z > 0) wideLo = std::min(wideLo, belowLo[k]), wideHi = std::max(wideHi, belowHi[k]);
                if (hasAbove) wideLo = std::min(wideLo, r.lo[i + slice]), wideHi = std::max(wideHi, r.hi[i + slice]);
                belowLo[k] = lo, belowHi[k] = hi;
                r.lo[i] = wideLo, r.hi[i] = wideHi;
            }
        }
    });
}

}  // namespace

FootprintRanges footprintRanges(const Vec3i& d, const std::vector<float>& scalars) {
    FootprintRanges r{std::vector<float>(scalars.size()), std::vector<float>(scalars.size())};
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
    tbb::parallel_for(tbb::blocked_range<int>(0, d.z), [&](const tbb::blocked_range<int>& zs) {
        std::vector<float> rowLo(slice), rowHi(slice);
        for (int z = zs.begin(); z != zs.end(); ++z) squareRanges(d, z, scalars, r, rowLo, rowHi);
    });
    acrossSlices(d, r);
    return r;
}

}  // namespace vr
