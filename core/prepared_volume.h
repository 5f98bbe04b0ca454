// Everything a renderer needs, as written by volprep and read by volrender.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "classified_volume.h"
#include "distance_fields.h"
#include "regions.h"

namespace vr {

struct PreparedMetadata {
    std::string source;            // input path
    std::string classification;    // transfer-function JSON text, or the iso-contour spec
    SegmentationParams segmentation;
    int distanceCap = kDistanceCap;
    nlohmann::json statistics;     // voxels, regions, timings, bytes: informative only
};

struct PreparedVolume {
    ClassifiedVolume classified;
    Regions regions;
    DistanceFields fields;
    PreparedMetadata meta;
};

}  // namespace vr
