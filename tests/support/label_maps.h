// Label maps for the tests: a volume's scalars thresholded into a few labels, and such a map written by VTK's own
// NIfTI writer (what a user's segmentation tool writes), to be read back as a user's would be.
#pragma once
#include <filesystem>
#include <vector>

#include "core/label_map.h"

namespace vr::test {

// Label i + 1 where the scalar is at or above thresholds[i] (the last such i), 0 below them all; type UInt8, the
// default palette's colours.
LabelMap thresholdLabels(const Volume& volume, const std::vector<float>& thresholds);

// `labels` (one value per voxel of `grid`, x fastest) written to `path` (.nii or .nii.gz) by vtkNIFTIImageWriter in
// `type`, with the grid's dims and spacing.
void writeNiftiWithVtk(const std::filesystem::path& path, const std::vector<float>& labels, const GridGeometry& grid,
                       ScalarType type);

}  // namespace vr::test
