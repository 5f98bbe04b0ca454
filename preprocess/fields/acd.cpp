// ACD (ALGORITHMS.md section 4): the 3D "largest cube" recurrence, one pass per octant.
#include <algorithm>

#include <tbb/parallel_for.h>

#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

// One x-row (y, z fixed) of the recurrence. Its 7 neighbours toward the octant lie in this row (the previous
// voxel of the scan, kept in a register) and in the rows (y+sy, z), (y, z+sz), (y+sy, z+sz), done before this
// row by the wavefront.
void acdRow(const Regions& regions, int octant, int y, int z, bool rowNeighbours, uint8_t* acd) {
    const Vec3i& n = regions.dims;
    const std::size_t row = linearIndex(n, 0, y, z);
    uint8_t* a0 = acd + row;
    if (!rowNeighbours) {  // a neighbour toward the octant is outside the volume
        std::fill(a0, a0 + n.x, uint8_t(1));
        return;
    }
    const int sx = octantSign(octant, 0);
    const std::ptrdiff_t dy = std::ptrdiff_t(octantSign(octant, 1)) * n.x,
                         dz = std::ptrdiff_t(octantSign(octant, 2)) * n.x * n.y;
    const uint32_t *l0 = regions.label.data() + row, *lY = l0 + dy, *lZ = l0 + dz, *lYZ = l0 + dy + dz;
    const uint8_t *aY = a0 + dy, *aZ = a0 + dz, *aYZ = a0 + dy + dz;
    int x = scanCoord(0, n.x, sx);
    a0[x] = 1;
    int previous = 1;  // acd at x + sx
    for (int i = 1; i < n.x; ++i) {
        x = scanCoord(i, n.x, sx);
        const int xn = x + sx;
        const uint32_t l = l0[x];
        const bool same = (l0[xn] == l) & (lY[x] == l) & (lY[xn] == l) & (lZ[x] == l) & (lZ[xn] == l) &
                          (lYZ[x] == l) & (lYZ[xn] == l);
        const int smallest = std::min({previous, int(aY[x]), int(aY[xn]), int(aZ[x]), int(aZ[xn]), int(aYZ[x]),
                                       int(aYZ[xn])});
        // Cap: a cube edge above 255 is stored as 255 (still a homogeneous cube, so still conservative).
        previous = same ? std::min(smallest + 1, kDistanceCap) : 1;
        a0[x] = uint8_t(previous);
    }
}

}  // namespace

std::vector<uint8_t> buildACD(const Regions& regions, int octant) {
    requireLabelPerVoxel(regions, "buildACD");
    if (octant < 0 || octant >= kOctants) throw std::invalid_argument("buildACD: no octant " + std::to_string(octant));
    const Vec3i& n = regions.dims;
    std::vector<uint8_t> acd(voxelCount(n));
    if (acd.empty()) return acd;
    const int sy = octantSign(octant, 1), sz = octantSign(octant, 2);
    // Wavefront over tiles of kTile x kTile (y, z) rows in scan order: row (yi, zi) needs rows (yi-1, zi),
    // (yi, zi-1) and (yi-1, zi-1), so a tile needs the tiles before it on each axis, and the tiles of one
    // anti-diagonal I + J = d are independent.
    constexpr int kTile = 8;
    const int tilesY = (n.y + kTile - 1) / kTile, tilesZ = (n.z + kTile - 1) / kTile;
    for (int d = 0; d <= (tilesY - 1) + (tilesZ - 1); ++d) {
        const int jLo = std::max(0, d - (tilesY - 1)), jHi = std::min(d, tilesZ - 1);
        tbb::parallel_for(jLo, jHi + 1, [&](int tj) {
            const int ti = d - tj;
            for (int zi = tj * kTile; zi < std::min(n.z, (tj + 1) * kTile); ++zi)
                for (int yi = ti * kTile; yi < std::min(n.y, (ti + 1) * kTile); ++yi)
                    acdRow(regions, octant, scanCoord(yi, n.y, sy), scanCoord(zi, n.z, sz), yi > 0 && zi > 0,
                           acd.data());
        });
    }
    return acd;
}

}  // namespace vr
