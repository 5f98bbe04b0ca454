// Homogeneous regions (docs/ALGORITHMS.md sections 3 and 9): a partition with bounded variation.
#pragma once
#include <vector>

#include "core/progress.h"
#include "core/regions.h"
#include "preprocess/segment/classified_voxels.h"

namespace vr {

// Regions are the 6-connected components of equal RegionKey (region_key.h), so the bound holds between ANY two
// voxels of a region: both transparent (sigma = 0), or opacity and each colour channel within T_o and normals
// within T_a (both flat, or both unit). With T_o = T_a = 0 a region is a connected run of bit-identical voxels
// (transparent voxels are identical whatever their colour and normal). With params.trilinear, voxels whose
// 26-neighbourhood touches another region are regions of one voxel. Labels 0..count-1 in first-voxel order.
// The voxels are classified as they are read (classified_voxels.h): no classified copy of the volume is made.
// Throws InputError for negative or NaN thresholds.
Regions segment(const ClassifiedVoxels& voxels, const SegmentationParams& params);
// The same into `regions`, reusing the memory of its labels: a segmentation of the same size then takes no fresh
// pages. On a throw `regions` is left in an unspecified state. `progress` hears how far it has come.
void segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, Regions& regions,
             const Progress& progress = {});

// The scalars that a transfer function classified, and how that function spreads over scalar intervals.
struct ClassifiedScalars {
    const std::vector<float>& values;  // x fastest, as the voxels
    const ClassificationSpread& spread;
};
// With params.trilinear, regions for post-classification (grown_regions.h): the interval of scalars that each
// region's interpolation footprints span classifies alike within T_o. Without it, segment() above.
void segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, const ClassifiedScalars& scalars,
             Regions& regions, const Progress& progress = {});
Regions segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, const ClassifiedScalars& scalars);

}  // namespace vr
