// Everything a renderer needs, as written by volprep and read by volrender.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "classified_volume.h"
#include "distance_fields.h"
#include "ray_probe.h"
#include "regions.h"

namespace vr {

struct PreparedMetadata {
    std::string source;            // input path
    std::string classification;    // transfer-function JSON text, or the iso-contour spec
    SegmentationParams segmentation;
    int distanceCap = kDistanceCap;
    nlohmann::json statistics;     // voxels, regions, timings, bytes: informative only
    std::optional<RayProbe> rayProbe;  // what --caster auto chooses from; none where rays are too long to probe
};

struct PreparedVolume {
    ClassifiedVolume classified;
    Regions regions;
    DistanceFields fields;
    PreparedMetadata meta;
};

// Bytes of each distance field, all octants together: what a caster's field costs to store and to upload.
struct FieldBytes {
    std::uint64_t pc = 0, acd = 0, eacd = 0;
};

inline FieldBytes fieldBytesOf(const DistanceFields& f) {
    FieldBytes b{f.pc.size(), 0, 0};
    for (int o = 0; o < kOctants; ++o) {
        b.acd += f.acd[o].size();
        b.eacd += f.eacd[o].bytes();
    }
    return b;
}

}  // namespace vr
