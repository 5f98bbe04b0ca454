#include "preprocess/pipeline/hier_field.h"

#include <stdexcept>

#include "core/errors.h"
#include "preprocess/classify/tf_range_table.h"
#include "preprocess/fields/block_eacd.h"
#include "preprocess/segment/block_regions.h"
#include "render/block_extrema.h"

namespace vr {
namespace {

// The transfer table as the renderers classify with it, its opacity per reference step: what the blocks' ranges are
// asked against (the float extinctions, so that entries equal on the device are equal here).
SampledTransferFunction tableSamples(const ScalarClassification& c) {
    SampledTransferFunction s{c.table.lo, c.table.step, std::vector<double>(c.table.size()), c.table.colour};
    for (std::size_t i = 0; i < c.table.size(); ++i)
        s.opacity[i] = opacityFromExtinction(c.table.sigma[i], c.referenceStep);
    return s;
}

}  // namespace

BlockEACD buildHierarchicalEACD(const PreparedVolume& classified, const SegmentationParams& params, unsigned octants,
                                int blockShift) {
    const int level = blockShift - device::kBlockShift;  // the block extrema's level of that edge
    if (level < 0 || level >= device::kBlockLevels)
        throw std::invalid_argument("buildHierarchicalEACD: blocks of 2^" + std::to_string(blockShift) +
                                    " voxels are not a level of the block extrema");
    if (classified.labels)
        throw InputError("the hier caster does not take a label map (--labels): its blocks are classified by the "
                         "scalars alone (use --caster eacd)");
    const TfRangeTable spread(tableSamples(classified.classification));
    const BlockExtrema extrema = blockExtrema(classified.scalars);
    const int edge = 1 << blockShift;
    const Vec3i d = classified.grid().dims;
    const Vec3i blocks{(d.x + edge - 1) >> blockShift, (d.y + edge - 1) >> blockShift, (d.z + edge - 1) >> blockShift};
    std::vector<EntryRange> ranges(voxelCount(blocks));
    std::size_t i = 0;
    for (int z = 0; z < blocks.z; ++z)
        for (int y = 0; y < blocks.y; ++y)
            for (int x = 0; x < blocks.x; ++x, ++i) {
                const Vec3i corner{x << blockShift, y << blockShift, z << blockShift};
                ranges[i] = {spread.entryBelow(extrema.lo(level, corner)),
                             spread.entryAbove(extrema.hi(level, corner))};
            }
    const BlockRegions regions = segmentBlocks(blocks, ranges, spread, params);
    return buildBlockEACD(regions.regions, regions.homogeneous, blockShift, octants);
}

}  // namespace vr
