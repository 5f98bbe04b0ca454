// Homogeneous regions (ALGORITHMS.md section 3): a partition with bounded variation.
#pragma once
#include "core/classified_volume.h"
#include "core/regions.h"

namespace vr {

// Throws InputError for negative or NaN thresholds.
Regions segment(const ClassifiedVolume& classified, const SegmentationParams& params);

}  // namespace vr
