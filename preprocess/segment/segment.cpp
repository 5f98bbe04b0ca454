#include "preprocess/segment/segment.h"

#include "preprocess/segment/border_regions.h"
#include "preprocess/segment/grown_regions.h"
#include "preprocess/segment/key_components.h"
#include "preprocess/segment/region_key.h"

namespace vr {

void segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, Regions& regions,
             const Progress& progress) {
    const RegionKeyer keyer(voxels, params);
    labelKeyComponents(voxels.grid().dims, keyer, regions);
    reportProgress(progress, 0.9);
    if (params.trilinear) splitBorderVoxels(regions);
    reportProgress(progress, 1);
}

Regions segment(const ClassifiedVoxels& voxels, const SegmentationParams& params) {
    Regions regions;
    segment(voxels, params, regions);
    return regions;
}

void segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, const ClassifiedScalars& scalars,
             Regions& regions, const Progress& progress) {
    if (!params.trilinear) return segment(voxels, params, regions, progress);
    growPostClassifiedRegions(voxels, params, scalars.values, scalars.spread, regions, progress);
}

Regions segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, const ClassifiedScalars& scalars) {
    Regions regions;
    segment(voxels, params, scalars, regions);
    return regions;
}

}  // namespace vr
