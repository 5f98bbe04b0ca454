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
    bool trilinear = false;         // regions whose interpolation footprints stay homogeneous (section 3 and 9)
    bool operator==(const SegmentationParams&) const = default;
};

// What post-classified segmentation asks of a transfer function (docs/ALGORITHMS.md section 9): an interpolated
// scalar anywhere in [lo, hi] may be classified, so the region is homogeneous only if the classification varies
// by at most the threshold over the whole interval. The interval is asked as the run of table entries that
// classify its scalars (first entryBelow(lo), last entryAbove(hi)): two bytes per end where a scalar takes four.
// Implemented by the classification's TfRangeTable.
class ClassificationSpread {
public:
    virtual ~ClassificationSpread() = default;
    // The entry at or below scalar f, and the entry at or above it (the same where f lies on an entry); both
    // monotone in f, below 65536.
    virtual uint16_t entryBelow(float f) const = 0;
    virtual uint16_t entryAbove(float f) const = 0;
    // Every entry first .. last transparent, or opacity and each colour channel spreading by at most `threshold`.
    virtual bool alikeEntries(uint16_t first, uint16_t last, double threshold) const = 0;
    // Every entry first .. last transparent (opacity 0).
    virtual bool clearEntries(uint16_t first, uint16_t last) const = 0;
    bool alike(float lo, float hi, double threshold) const {
        return alikeEntries(entryBelow(lo), entryAbove(hi), threshold);
    }
};

struct Regions {
    Vec3i dims{0, 0, 0};
    std::vector<uint32_t> label;  // region id per voxel, x fastest
    uint32_t count = 0;           // ids are 0 .. count-1

    bool same(std::size_t a, std::size_t b) const { return label[a] == label[b]; }
};

}  // namespace vr
