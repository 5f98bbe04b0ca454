#include "preprocess/segment/segment.h"

#include "preprocess/segment/border_regions.h"
#include "preprocess/segment/grown_regions.h"
#include "preprocess/segment/key_components.h"
#include "preprocess/segment/region_key.h"

namespace vr {

void segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, Regions& regions) {
    const RegionKeyer keyer(voxels, params);
    labelKeyComponents(voxels.grid().dims, keyer, regions);
    if (params.trilinear) splitBorderVoxels(regions);
}

Regions segment(const ClassifiedVoxels& voxels, const SegmentationParams& params) {
    Regions regions;
    segment(voxels, params, regions);
    return regions;
}

void segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, const ClassifiedScalars& scalars,
             Regions& regions) {
    if (!params.trilinear) return segment(voxels, params, regions);
    growPostClassifiedRegions(voxels, params, scalars.values, scalars.spread, regions);
}

Regions segment(const ClassifiedVoxels& voxels, const SegmentationParams& params, const ClassifiedScalars& scalars) {
    Regions regions;
    segment(voxels, params, scalars, regions);
    return regions;
}

}  // namespace vr
