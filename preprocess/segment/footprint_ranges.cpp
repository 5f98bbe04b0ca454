#include "preprocess/segment/footprint_ranges.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace vr {
namespace {

EntryRange widened(EntryRange a, EntryRange b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }

// The range over the 3x3 square of each voxel of slice z (x then y, separable), in place: the slice's own ranges
// are read into `rows` (along x) before any of its slots is written.
void squareRanges(const Vec3i& d, int z, std::vector<EntryRange>& r, std::vector<EntryRange>& rows) {
    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y), base = linearIndex(d, 0, 0, z);
    for (std::size_t row = 0; row < slice; row += nx)
        for (std::size_t x = 0; x < nx; ++x) {
            const std::size_t j = row + x, i = base + j;
            rows[j] = widened(widened(r[x == 0 ? i : i - 1], r[i]), r[x + 1 == nx ? i : i + 1]);
        }
    for (std::size_t j = 0; j < slice; ++j) {
        const std::size_t up = j < nx ? j : j - nx, down = j + nx >= slice ? j : j + nx;
        r[base + j] = widened(widened(rows[up], rows[j]), rows[down]);
    }
}

// Each voxel's square range widened by the squares beside it along z, in place: a column block at a time,
// keeping the block's square ranges of the slice below before they are overwritten.
void acrossSlices(const Vec3i& d, std::vector<EntryRange>& r) {
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slice, 4096), [&](const tbb::blocked_range<std::size_t>& js) {
        std::vector<EntryRange> below(js.size());
        for (int z = 0; z < d.z; ++z) {
            const std::size_t base = linearIndex(d, 0, 0, z) + js.begin();
            for (std::size_t k = 0; k < js.size(); ++k) {
                const std::size_t i = base + k;
                const EntryRange square = r[i];
                EntryRange wide = square;
                if (z > 0) wide = widened(wide, below[k]);
                if (z + 1 < d.z) wide = widened(wide, r[i + slice]);
                below[k] = square;
                r[i] = wide;
            }
        }
    });
}

}  // namespace

std::vector<EntryRange> footprintRanges(const Vec3i& d, const std::vector<float>& scalars,
                                        const ClassificationSpread& spread) {
    std::vector<EntryRange> r(scalars.size());
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
    tbb::parallel_for(tbb::blocked_range<int>(0, d.z), [&](const tbb::blocked_range<int>& zs) {
        std::vector<EntryRange> rows(slice);
        for (int z = zs.begin(); z != zs.end(); ++z) {
            const std::size_t base = linearIndex(d, 0, 0, z);
            // Neighbours often share their scalar (air, flat tissue): look each run of them up once.
            float last = scalars[base];
            EntryRange entries{spread.entryBelow(last), spread.entryAbove(last)};
            for (std::size_t i = base; i < base + slice; ++i) {
                if (scalars[i] != last) {
                    last = scalars[i];
                    entries = {spread.entryBelow(last), spread.entryAbove(last)};
                }
                r[i] = entries;
            }
            squareRanges(d, z, r, rows);
        }
    });
    acrossSlices(d, r);
    return r;
}

}  // namespace vr
