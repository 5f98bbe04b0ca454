// ACD (ALGORITHMS.md section 4): the 3D "largest cube" recurrence, one pass per octant.
#include <algorithm>

#include <tbb/parallel_for.h>

#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

// One x-row (y, z fixed) of the recurrence. Its 7 neighbours toward the octant lie in this row (done earlier in
// the scan) and in the rows (y+sy, z), (y, z+sz), (y+sy, z+sz), done before this row by the wavefront.
void acdRow(const Regions& regions, int octant, int y, int z, bool rowNeighbours, uint8_t* acd) {
    const Vec3i& n = regions.dims;
    const int sx = octantSign(octant, 0);
    const std::ptrdiff_t dx = sx, dy = std::ptrdiff_t(octantSign(octant, 1)) * n.x,
                         dz = std::ptrdiff_t(octantSign(octant, 2)) * n.x * n.y;
    const std::ptrdiff_t offsets[7] = {dx, dy, dx + dy, dz, dx + dz, dy + dz, dx + dy + dz};
    const std::size_t row = linearIndex(n, 0, y, z);
    const uint32_t* label = regions.label.data();
    for (int i = 0; i < n.x; ++i) {
        const std::size_t v = row + std::size_t(scanCoord(i, n.x, sx));
        if (i == 0 || !rowNeighbours) {
            acd[v] = 1;  // a neighbour toward the octant is outside the volume
            continue;
        }
        bool same = true;
        int smallest = kDistanceCap;
        for (std::ptrdiff_t o : offsets) {
            same &= label[v + o] == label[v];
            smallest = std::min<int>(smallest, acd[v + o]);
        }
        // Cap: a cube edge above 255 is stored as 255 (still a homogeneous cube, so still conservative).
        acd[v] = same ? uint8_t(std::min(smallest + 1, kDistanceCap)) : uint8_t(1);
    }
}

}  // namespace

std::vector<uint8_t> buildACD(const Regions& regions, int octant) {
    requireLabelPerVoxel(regions, "buildACD");
    const Vec3i& n = regions.dims;
    std::vector<uint8_t> acd(voxelCount(n));
    if (acd.empty()) return acd;
    const int sy = octantSign(octant, 1), sz = octantSign(octant, 2);
    // Wavefront over the (y, z) rows in scan order: row (yi, zi) needs rows (yi-1, zi), (yi, zi-1), (yi-1, zi-1),
    // so the rows of one anti-diagonal yi + zi = d are independent.
    for (int d = 0; d <= (n.y - 1) + (n.z - 1); ++d) {
        const int ziLo = std::max(0, d - (n.y - 1)), ziHi = std::min(d, n.z - 1);
        tbb::parallel_for(ziLo, ziHi + 1, [&](int zi) {
            const int yi = d - zi;
            acdRow(regions, octant, scanCoord(yi, n.y, sy), scanCoord(zi, n.z, sz), yi > 0 && zi > 0, acd.data());
        });
    }
    return acd;
}

}  // namespace vr
