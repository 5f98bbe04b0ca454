// A volume prepared for rendering in tests: classified, segmented and given its distance fields, the stages run
// directly (no statistics, no ray probe: the pipeline's own prepare() adds those, and its test compares with it).
#pragma once
#include <optional>

#include "core/prepared_volume.h"
#include "core/volume.h"
#include "preprocess/classify/transfer_function.h"

namespace vr::test {

inline constexpr unsigned kAllFields = kRegionFields | kFieldHier;

// Classifies `volume` with `tf` (normals when segmentation.useNormals) and `labels` where given (their colours
// classified), segments it with `segmentation` and builds `fields` (the hier field as volrender builds it, from the
// scalars); meta.source and meta.segmentation say so.
PreparedVolume prepareVolume(const Volume& volume, const TransferFunction& tf, const SegmentationParams& segmentation,
                             unsigned fields = kAllFields, std::optional<LabelMap> labels = std::nullopt);

}  // namespace vr::test
