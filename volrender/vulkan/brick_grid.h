// How a volume is split into bricks whose images each fit the device: a grid of boxes along the axes, each brick's
// images holding its core plus kBrickMargin voxels on every side: a trilinear sample in the core reads the corners
// of its cell, up to one voxel beyond the core, and, shaded, their central differences, one voxel further.
#pragma once
#include <functional>
#include <vector>

#include "core/vec3.h"

namespace vr {

inline constexpr int kBrickMargin = 2;

struct Brick {
    Vec3i lo, hi;            // core, inclusive: the voxels whose samples this brick renders
    Vec3i imageLo, imageDims;  // the voxels its images hold: the core grown by kBrickMargin voxels, within the volume
};

class BrickGrid {
public:
    BrickGrid() = default;
    // counts[a] bricks along axis a, cores of floor(i N / n) .. floor((i + 1) N / n) - 1 voxels.
    BrickGrid(const Vec3i& dims, const Vec3i& counts);

    const Vec3i& counts() const { return counts_; }
    const std::vector<Brick>& bricks() const { return bricks_; }  // x fastest
    // Bit a set when the volume is split along axis a.
    unsigned splitAxes() const;
    // The largest image extent of any brick, per axis.
    Vec3i largestImage() const;
    // Brick indices in an order that every ray of the given signs meets them in: `signs` has bit a set for rays
    // going toward -a (octantOf), only its bits on split axes matter. A ray's voxels are monotone along each axis,
    // so the bricks it crosses increase in this lexicographic order.
    std::vector<int> frontToBack(unsigned signs) const;

private:
    Vec3i counts_{1, 1, 1};
    std::vector<Brick> bricks_;
};

// Starting from `minBricks` bricks per axis (at most one per voxel), splits along the axis whose image is longest
// (z counted `zSlabs` times: ACD/EACD stack their octants along z) until fits(largest image extent) holds. Throws
// std::runtime_error when even one-voxel cores do not fit.
BrickGrid planBricks(const Vec3i& dims, int zSlabs, const std::function<bool(const Vec3i&)>& fits,
                     const Vec3i& minBricks = {1, 1, 1});

}  // namespace vr
