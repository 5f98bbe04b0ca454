#include "preprocess/segment/segment.h"

#include "core/errors.h"
#include "preprocess/segment/border_regions.h"
#include "preprocess/segment/key_components.h"
#include "preprocess/segment/region_key.h"

namespace vr {

void segment(const ClassifiedVolume& classified, const SegmentationParams& params, Regions& regions) {
    const std::size_t n = classified.grid.voxels();
    if (n == 0 || classified.sigma.size() != n || classified.colour.size() != n ||
        (classified.hasNormals() && classified.normal.size() != n))
        throw InputError("segmentation: the classified volume is empty or its arrays do not match its dimensions");
    const RegionKeyer keyer(classified, params);
    labelKeyComponents(classified.grid.dims, keyer, regions);
    if (params.trilinear) splitBorderVoxels(regions);
}

Regions segment(const ClassifiedVolume& classified, const SegmentationParams& params) {
    Regions regions;
    segment(classified, params, regions);
    return regions;
}

}  // namespace vr
