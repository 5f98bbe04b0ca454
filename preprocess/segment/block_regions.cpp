#include "preprocess/segment/block_regions.h"

#include "core/errors.h"
#include "preprocess/segment/grown_regions.h"
#include "preprocess/segment/region_key.h"

namespace vr {

BlockRegions segmentBlocks(const Vec3i& blocks, const std::vector<EntryRange>& ranges,
                           const ClassificationSpread& spread, const SegmentationParams& params) {
    checkThresholds(params);
    const std::size_t n = voxelCount(blocks);
    if (ranges.size() != n) throw InputError("block segmentation: the ranges do not match the blocks");
    BlockRegions b;
    b.homogeneous.resize(n);
    b.regions.dims = blocks;
    b.regions.label.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const EntryRange r = ranges[i];
        const bool alike = params.useNormals ? spread.clearEntries(r.lo, r.hi)
                                             : spread.alikeEntries(r.lo, r.hi, params.opacityThreshold);
        b.homogeneous[i] = alike;
        b.regions.label[i] = alike ? kUnsetCell : kBorderCell;
    }
    b.regions.count = growRegions(blocks, ranges, spread, params.opacityThreshold, b.regions.label);
    return b;
}

}  // namespace vr
