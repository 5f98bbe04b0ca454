// Geometry of a voxel grid: voxel v covers the grid cell [v, v+1); world = origin + grid * spacing.
#pragma once
#include "vec3.h"

namespace vr {

struct GridGeometry {
    Vec3i dims{0, 0, 0};
    Vec3d spacing{1, 1, 1};  // physical size of one voxel (e.g. mm)
    Vec3d origin{0, 0, 0};   // world position of the corner of voxel (0,0,0)

    std::size_t voxels() const { return voxelCount(dims); }
    Vec3d extent() const { return Vec3d(dims) * spacing; }
    Vec3d centre() const { return origin + extent() * 0.5; }
    double smallestSpacing() const { return minComponent(spacing); }
    bool operator==(const GridGeometry&) const = default;
};

}  // namespace vr
