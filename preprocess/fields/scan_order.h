// Scan orders of the field recurrences: a value at v depends on its neighbours toward the octant, so those come first.
#pragma once
#include <stdexcept>
#include <string>

#include "core/regions.h"

namespace vr {

// Coordinate of the i-th voxel scanned along an axis of n voxels when v depends on v + sign:
// sign +1 scans n-1 down to 0, sign -1 scans 0 up to n-1. i == 0 is the voxel whose neighbour lies outside.
constexpr int scanCoord(int i, int n, int sign) { return sign > 0 ? n - 1 - i : i; }

// The fields index the labels by voxel: a Regions whose label count does not match its dims is a caller's bug.
inline void requireLabelPerVoxel(const Regions& regions, const char* who) {
    if (regions.dims.x < 0 || regions.dims.y < 0 || regions.dims.z < 0 ||
        regions.label.size() != voxelCount(regions.dims))
        throw std::invalid_argument(std::string(who) + ": regions hold " + std::to_string(regions.label.size()) +
                                    " labels for dims " + std::to_string(regions.dims.x) + "x" +
                                    std::to_string(regions.dims.y) + "x" + std::to_string(regions.dims.z));
}

}  // namespace vr
