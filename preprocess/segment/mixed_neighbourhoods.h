// Voxels whose 26-neighbourhood mixes classes: where trilinear interpolation reads across them
// (docs/ALGORITHMS.md sections 3 and 9).
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace vr {
namespace mixed_detail {

// uniform[j] = 1 when the 3x3 voxels around voxel j of slice z (in x and y, clamped at the volume's edge) are all
// `same` as it; `triples` is scratch for the same test along x alone. Separable, so 4 comparisons per voxel, not 9.
template <typename Same>
void uniformSquares(const Vec3i& d, int z, Same& same, std::vector<uint8_t>& triples, std::vector<uint8_t>& uniform) {
    const std::size_t base = linearIndex(d, 0, 0, z);
    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y);
    for (std::size_t row = 0; row < slice; row += nx)
        for (std::size_t x = 0; x < nx; ++x) {
            const std::size_t j = row + x, i = base + j;
            triples[j] = (x == 0 || same(i - 1, i)) && (x + 1 == nx || same(i + 1, i));
        }
    for (std::size_t j = 0; j < slice; ++j) {
        const std::size_t i = base + j;
        uniform[j] = triples[j] && (j < nx || (triples[j - nx] && same(i - nx, i))) &&
                     (j + nx >= slice || (triples[j + nx] && same(i + nx, i)));
    }
}

}  // namespace mixed_detail

// mixed[i] = 1 where voxel i has one of its 26 neighbours inside the volume not `same` as it. `same(a, b)` must be
// an equivalence over voxel indices (then 3x3 squares and their stacks test the whole neighbourhood) and safe to
// call from several threads. Slabs of slices in parallel, each keeping the squares of three slices.
template <typename Same>
std::vector<uint8_t> mixedNeighbourhoods(const Vec3i& d, Same same) {
    const std::size_t slice = std::size_t(d.x) * std::size_t(d.y);
    std::vector<uint8_t> mixed(slice * std::size_t(d.z));
    tbb::parallel_for(tbb::blocked_range<int>(0, d.z), [&](const tbb::blocked_range<int>& zs) {
        std::vector<uint8_t> triples(slice), below(slice), here(slice), above(slice);
        if (zs.begin() > 0) mixed_detail::uniformSquares(d, zs.begin() - 1, same, triples, below);
        mixed_detail::uniformSquares(d, zs.begin(), same, triples, here);
        for (int z = zs.begin(); z != zs.end(); ++z) {
            if (z + 1 < d.z) mixed_detail::uniformSquares(d, z + 1, same, triples, above);
            const std::size_t base = linearIndex(d, 0, 0, z);
            for (std::size_t j = 0; j < slice; ++j) {
                const std::size_t i = base + j;
                mixed[i] = !(here[j] && (z == 0 || (below[j] && same(i - slice, i))) &&
                             (z + 1 == d.z || (above[j] && same(i + slice, i))));
            }
            std::swap(below, here);
            std::swap(here, above);
        }
    });
    return mixed;
}

}  // namespace vr
