// Homogeneous regions (docs/ALGORITHMS.md section 3): a partition of the voxels into labelled regions.
#pragma once
#include <cstdint>
#include <vector>

#include "vec3.h"

namespace vr {

struct SegmentationParams {
    double opacityThreshold = 0.0;  // T_o: opacity (and colour) variation allowed within a region
    double angleThresholdDeg = 0.0; // T_a: normal angle allowed within a region, degrees
    bool useNormals = true;         // false when shading is off: normals are then ignored
    bool trilinear = false;         // border voxels of the 2x2x2 footprint become regions of their own
    bool operator==(const SegmentationParams&) const = default;
};

struct Regions {
    Vec3i dims{0, 0, 0};
    std::vector<uint32_t> label;  // region id per voxel, x fastest
    uint32_t count = 0;           // ids are 0 .. count-1

    bool same(std::size_t a, std::size_t b) const { return label[a] == label[b]; }
};

}  // namespace vr
