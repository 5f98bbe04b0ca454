#include "preprocess/segment/border_regions.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <limits>

namespace vr {
namespace {

// uniform[j] = 1 when the 3x3 voxels around voxel j of slice z (in x and y, clamped at the volume's edge) all have
// its label; `triples` is scratch for the same test along x alone. Separable, so 4 comparisons per voxel, not 9.
void uniformSquares(const Regions& regions, int z, std::vector<uint8_t>& triples, std::vector<uint8_t>& uniform) {
    const Vec3i& d = regions.dims;
    const uint32_t* l = &regions.label[linearIndex(d, 0, 0, z)];
    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y);
    for (std::size_t row = 0; row < slice; row += nx)
        for (std::size_t x = 0; x < nx; ++x) {
            const std::size_t j = row + x;
            triples[j] = (x == 0 || l[j - 1] == l[j]) && (x + 1 == nx || l[j + 1] == l[j]);
        }
    for (std::size_t j = 0; j < slice; ++j)
        uniform[j] = triples[j] && (j < nx || (triples[j - nx] && l[j - nx] == l[j])) &&
                     (j + nx >= slice || (triples[j + nx] && l[j + nx] == l[j]));
}

}  // namespace

void splitBorderVoxels(Regions& regions) {
    const Vec3i d = regions.dims;
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
    std::vector<uint8_t> border(regions.label.size());
    // A voxel is a border voxel unless the 3x3 squares of its slice and of the slices beside it are uniform in its
    // label. Slabs of slices in parallel, each keeping the squares of three slices.
    tbb::parallel_for(tbb::blocked_range<int>(0, d.z), [&](const tbb::blocked_range<int>& zs) {
        std::vector<uint8_t> triples(slice), below(slice), here(slice), above(slice);
        if (zs.begin() > 0) uniformSquares(regions, zs.begin() - 1, triples, below);
        uniformSquares(regions, zs.begin(), triples, here);
        for (int z = zs.begin(); z != zs.end(); ++z) {
            if (z + 1 < d.z) uniformSquares(regions, z + 1, triples, above);
            const uint32_t* l = &regions.label[linearIndex(d, 0, 0, z)];
            const uint32_t* lBelow = z > 0 ? l - slice : l;  // read only when the slice exists
            const uint32_t* lAbove = z + 1 < d.z ? l + slice : l;
            uint8_t* b = &border[linearIndex(d, 0, 0, z)];
            for (std::size_t j = 0; j < slice; ++j)
                b[j] = !(here[j] && (z == 0 || (below[j] && lBelow[j] == l[j])) &&
                         (z + 1 == d.z || (above[j] && lAbove[j] == l[j])));
            std::swap(below, here);
            std::swap(here, above);
        }
    });
    // Relabel in voxel order: a border voxel takes a fresh label, the rest their region's (a region may vanish).
    constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> relabel(regions.count, kUnset);
    uint32_t count = 0;
    for (std::size_t i = 0; i < regions.label.size(); ++i) {
        if (border[i]) {
            regions.label[i] = count++;
        } else {
            uint32_t& to = relabel[regions.label[i]];
            if (to == kUnset) to = count++;
            regions.label[i] = to;
        }
    }
    regions.count = count;
}

}  // namespace vr
