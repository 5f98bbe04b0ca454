// ACD (docs/ALGORITHMS.md section 4) from the axial runs toward the octant, one z-layer at a time. With x, y, z one
// step toward the octant and sq the largest square of the xy layer cornered at v:
//   sq[v]  = min(runX[v], runX[v+y], runY[v], 1 + sq[v+y], 1 + sq[v+x+y])
//   acd[v] = min(sq[v], sq[v+z], runZ[v], 1 + min(acd[v+z], acd[v+x+z], acd[v+y+z], acd[v+x+y+z]))
// A square of edge k >= 2 is its first row and the two squares of edge k-1 on the next row, tied to v's region by
// runY[v] >= 2 and runX[v+y] >= 2; a cube is its first layer and the four cubes of edge k-1 on the next layer,
// tied by runZ[v] >= 2 and sq[v+z] >= 2. Every term is also at least the true edge, so the minimum is exact: the
// 7-neighbour cube recurrence, but with no label compare and every voxel of a row independent (16 at a time).
// Capped terms (255) give min(edge, 255), the cap of the recurrence.
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "preprocess/fields/axial_runs.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

class OctantPass {
public:
    OctantPass(AxialRuns& runs, int octant)
        : n_(runs.dims()), sx_(octantSign(octant, 0)), sy_(octantSign(octant, 1)), sz_(octantSign(octant, 2)),
          plane_(std::size_t(n_.x) * n_.y), runX_(runs.get(0, sx_).data()), runY_(runs.get(1, sy_).data()),
          runZ_(runs.get(2, sz_).data()) {}

    // Layer i's squares are independent of layer i-1's cubes, so the two run at once (the chain of layers is
    // serial); three square layers rotate: i, and i-1 and i-2 for the cubes of i-1.
    void run(uint8_t* acd) const {
        std::array<std::vector<uint8_t>, 3> sq;
        for (auto& layer : sq) layer.resize(plane_);
        for (int i = 0; i <= n_.z; ++i) {
            auto squares = [&] { if (i < n_.z) squareLayer(i, sq[i % 3].data()); };
            auto cubes = [&] { if (i > 0) cubeLayer(i - 1, sq[(i - 1) % 3].data(), sq[(i + 1) % 3].data(), acd); };
            tbb::parallel_invoke(squares, cubes);
        }
    }

private:
    // The voxels of a row whose neighbour toward the octant along x is inside: [first(), first() + n.x - 1); the
    // remaining one, borderX(), has runX = 1, so every field is 1 there.
    int first() const { return sx_ > 0 ? 0 : 1; }
    int borderX() const { return sx_ > 0 ? n_.x - 1 : 0; }

    void squareLayer(int zi, uint8_t* sq) const {
        const std::size_t layer = std::size_t(scanCoord(zi, n_.z, sz_)) * plane_;
        const std::ptrdiff_t dy = std::ptrdiff_t(sy_) * n_.x;
        for (int yi = 0; yi < n_.y; ++yi) {
            const std::size_t row = std::size_t(scanCoord(yi, n_.y, sy_)) * n_.x;
            uint8_t* s = sq + row;
            if (yi == 0 || n_.x == 1) {  // runY or runX is 1
                std::fill(s, s + n_.x, uint8_t(1));
                continue;
            }
            const int f = first();
            const uint8_t *rx = runX_ + layer + row + f, *ry = runY_ + layer + row + f, *up = s + dy + f;
            forEachLane(n_.x - 1, [&, sx = sx_](std::size_t k, auto t) {
                store(s + f + k, minOf(minOf(load(rx + k, t), load(rx + dy + k, t)),
                                       minOf(load(ry + k, t), plusOne(minOf(load(up + k, t), load(up + sx + k, t))))));
            });
            s[borderX()] = 1;
        }
    }

    void cubeLayer(int zi, const uint8_t* sq, const uint8_t* sqBelow, uint8_t* acd) const {
        const std::size_t layer = std::size_t(scanCoord(zi, n_.z, sz_)) * plane_;
        uint8_t* a = acd + layer;
        if (zi == 0 || n_.x == 1) {  // runZ or runX is 1
            std::fill(a, a + plane_, uint8_t(1));
            return;
        }
        const std::ptrdiff_t dy = std::ptrdiff_t(sy_) * n_.x, dz = std::ptrdiff_t(sz_) * std::ptrdiff_t(plane_);
        for (int yi = 0; yi < n_.y; ++yi) {
            const std::size_t row = std::size_t(scanCoord(yi, n_.y, sy_)) * n_.x;
            uint8_t* out = a + row;
            if (yi == 0) {  // runY is 1, so sq is
                std::fill(out, out + n_.x, uint8_t(1));
                continue;
            }
            const int f = first();
            const uint8_t *s = sq + row + f, *below = sqBelow + row + f, *rz = runZ_ + layer + row + f;
            const uint8_t* next = out + f + dz;  // the layer toward the octant, done
            forEachLane(n_.x - 1, [&, sx = sx_](std::size_t k, auto t) {
                const auto nextMin = minOf(minOf(load(next + k, t), load(next + sx + k, t)),
                                           minOf(load(next + dy + k, t), load(next + dy + sx + k, t)));
                store(out + f + k,
                      minOf(minOf(load(s + k, t), load(below + k, t)), minOf(load(rz + k, t), plusOne(nextMin))));
            });
            out[borderX()] = 1;
        }
    }

    Vec3i n_;
    int sx_, sy_, sz_;
    std::size_t plane_;
    const uint8_t *runX_, *runY_, *runZ_;
};

}  // namespace

std::vector<uint8_t> buildACD(AxialRuns& runs, int octant) {
    if (octant < 0 || octant >= kOctants) throw std::invalid_argument("buildACD: no octant " + std::to_string(octant));
    std::vector<uint8_t> acd(voxelCount(runs.dims()));
    if (!acd.empty()) OctantPass(runs, octant).run(acd.data());
    return acd;
}

std::vector<uint8_t> buildACD(const Regions& regions, int octant) {
    AxialRuns runs(regions);
    return buildACD(runs, octant);
}

ACDFields buildACDs(AxialRuns& runs, unsigned octants) {
    ACDFields acd;
    if (voxelCount(runs.dims()) == 0) return acd;
    runs.computeAll(octants);
    tbb::parallel_for(0, kOctants, [&](int o) {
        if (octants >> o & 1u) acd[o] = buildACD(runs, o);
    });
    return acd;
}

}  // namespace vr
