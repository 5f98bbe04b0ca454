#include "preprocess/pipeline/hier_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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
    if (blockShift < 1)
        throw std::invalid_argument("buildHierarchicalEACD: blocks of 2^" + std::to_string(blockShift) +
                                    " voxels: a block must be 2 voxels or more per axis");
    if (classified.labels)
        throw InputError("the hier caster does not take a label map (--labels): its blocks are classified by the "
                         "scalars alone (use --caster eacd)");
    const TfRangeTable spread(tableSamples(classified.classification));
    const BlockRanges scalarRanges = blockRanges(classified.scalars, blockShift);
    std::vector<EntryRange> ranges(voxelCount(scalarRanges.blocks));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ranges.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
            ranges[i] = {spread.entryBelow(scalarRanges.range[2 * i]),
                         spread.entryAbove(scalarRanges.range[2 * i + 1])};
    });
    const BlockRegions regions = segmentBlocks(scalarRanges.blocks, ranges, spread, params);
    return buildBlockEACD(regions.regions, regions.homogeneous, blockShift, octants);
}

}  // namespace vr
