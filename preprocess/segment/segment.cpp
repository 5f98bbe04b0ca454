#include "preprocess/segment/segment.h"

#include "core/errors.h"
#include "preprocess/segment/border_regions.h"
#include "preprocess/segment/grown_regions.h"
#include "preprocess/segment/key_components.h"
#include "preprocess/segment/region_key.h"

namespace vr {
namespace {

void checkClassified(const ClassifiedVolume& classified) {
    const std::size_t n = classified.grid.voxels();
    if (n == 0 || classified.sigma.size() != n || classified.colour.size() != n ||
        (classified.hasNormals() && classified.normal.size() != n))
        throw InputError("segmentation: the classified volume is empty or its arrays do not match its dimensions");
}

}  // namespace

void segment(const ClassifiedVolume& classified, const SegmentationParams& params, Regions& regions) {
    checkClassified(classified);
    const RegionKeyer keyer(classified, params);
    labelKeyComponents(classified.grid.dims, keyer, regions);
    if (params.trilinear) splitBorderVoxels(regions);
}

Regions segment(const ClassifiedVolume& classified, const SegmentationParams& params) {
    Regions regions;
    segment(classified, params, regions);
    return regions;
}

void segment(const ClassifiedVolume& classified, const SegmentationParams& params, const ClassifiedScalars& scalars,
             Regions& regions) {
    if (!params.trilinear) return segment(classified, params, regions);
    checkClassified(classified);
    growPostClassifiedRegions(classified, params, scalars.values, scalars.spread, regions);
}

Regions segment(const ClassifiedVolume& classified, const SegmentationParams& params, const ClassifiedScalars& scalars) {
    Regions regions;
    segment(classified, params, scalars, regions);
    return regions;
}

}  // namespace vr
