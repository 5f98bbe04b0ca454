// Everything a renderer needs, as written by volprep and read by volrender.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "distance_fields.h"
#include "label_map.h"
#include "ray_probe.h"
#include "regions.h"
#include "scalar_classification.h"
#include "volume.h"

namespace vr {

struct PreparedMetadata {
    std::string source;            // input path
    std::string classification;    // transfer-function JSON text, or the iso-contour spec
    SegmentationParams segmentation;
    int distanceCap = kDistanceCap;
    nlohmann::json statistics;     // voxels, regions, timings, bytes: informative only
    std::optional<RayProbe> rayProbe;  // what --caster auto chooses from; none where rays are too long to probe
};

// The scalars and how to classify them (the renderers classify each sample: docs/ALGORITHMS.md section 2), with a
// label map where one was given, the regions and the fields over them.
struct PreparedVolume {
    Volume scalars;  // held as float; scalars.sourceType is how the device and the prepared file hold them
    ScalarClassification classification;
    std::optional<LabelMap> labels;  // a label map beside the scalars, classified with them
    Regions regions;
    DistanceFields fields;
    PreparedMetadata meta;

    const GridGeometry& grid() const { return scalars.grid; }
};

// Bytes of each distance field, all octants together: what a caster's field costs to store and to upload.
struct FieldBytes {
    std::uint64_t pc = 0, acd = 0, eacd = 0, hier = 0;
};

inline FieldBytes fieldBytesOf(const DistanceFields& f) {
    FieldBytes b{f.pc.size(), 0, 0, f.hier.bytes()};
    for (int o = 0; o < kOctants; ++o) {
        b.acd += f.acd[o].size();
        b.eacd += f.eacd[o].bytes();
    }
    return b;
}

}  // namespace vr
