#include "volrender/vulkan/brick_grid.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <tuple>

namespace vr {

BrickGrid::BrickGrid(const Vec3i& dims, const Vec3i& counts) : counts_(counts) {
    auto cut = [&](int a, int i) { return int(int64_t(i) * dims[a] / counts[a]); };
    for (int z = 0; z < counts.z; ++z)
        for (int y = 0; y < counts.y; ++y)
            for (int x = 0; x < counts.x; ++x) {
                const Vec3i index{x, y, z};
                Brick b;
                for (int a = 0; a < 3; ++a) {
                    b.lo[a] = cut(a, index[a]);
                    b.hi[a] = cut(a, index[a] + 1) - 1;
                    b.imageLo[a] = std::max(0, b.lo[a] - kBrickMargin);
                    b.imageDims[a] = std::min(dims[a] - 1, b.hi[a] + kBrickMargin) - b.imageLo[a] + 1;
                }
                bricks_.push_back(b);
            }
}

unsigned BrickGrid::splitAxes() const {
    return unsigned(counts_.x > 1) | unsigned(counts_.y > 1) << 1 | unsigned(counts_.z > 1) << 2;
}

Vec3i BrickGrid::largestImage() const {
    Vec3i m{0, 0, 0};
    for (const Brick& b : bricks_)
        for (int a = 0; a < 3; ++a) m[a] = std::max(m[a], b.imageDims[a]);
    return m;
}

std::vector<int> BrickGrid::frontToBack(unsigned signs) const {
    std::vector<int> order(bricks_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    // Index i = x + counts.x (y + counts.y z); an axis toward -a visits its bricks from the top.
    auto key = [&](int i) {
        Vec3i c{i % counts_.x, (i / counts_.x) % counts_.y, i / (counts_.x * counts_.y)};
        for (int a = 0; a < 3; ++a)
            if (signs >> a & 1) c[a] = counts_[a] - 1 - c[a];
        return std::make_tuple(c.z, c.y, c.x);
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
    return order;
}

BrickGrid planBricks(const Vec3i& dims, int zSlabs, const std::function<bool(const Vec3i&)>& fits,
                     const Vec3i& minBricks) {
    Vec3i counts;
    for (int a = 0; a < 3; ++a) counts[a] = std::clamp(minBricks[a], 1, std::max(1, dims[a]));
    for (;;) {
        BrickGrid grid(dims, counts);
        const Vec3i largest = grid.largestImage();
        if (fits(largest)) return grid;
        // The longest image axis that can still be cut (cores of at least one voxel).
        int axis = -1;
        int64_t longest = 0;
        for (int a = 0; a < 3; ++a) {
            const int64_t length = int64_t(largest[a]) * (a == 2 ? zSlabs : 1);
            if (counts[a] < dims[a] && length > longest) axis = a, longest = length;
        }
        if (axis < 0)
            throw std::runtime_error("the volume cannot be split into bricks that fit the device: even a brick of "
                                     "one voxel (5x5x5 with the neighbours it reads) exceeds its image limits");
        // Grow by about an eighth so that huge volumes need few plans, at least by one brick.
        counts[axis] = std::min(dims[axis], counts[axis] + std::max(1, counts[axis] / 8));
    }
}

}  // namespace vr
