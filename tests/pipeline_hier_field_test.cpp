// The hierarchical EACD's coarse level (docs/ALGORITHMS.md section 10): which blocks are homogeneous, their boxes in
// blocks up to a volume border that cuts the last block short, a narrow TF peak that is never leapt over, and its
// preparation without any per-voxel segmentation.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/classify.h"
#include "preprocess/pipeline/hier_field.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "render/camera.h"
#include "render/cpu_renderer.h"

namespace vr {
namespace {

// Transparent at 0 and up to 15, a narrow opaque peak at 20, transparent again from 25 (volume values 0..255).
const TransferFunction& peakTf() {
    static const TransferFunction tf = parseTransferFunction(R"({
        "Points": [0, 0, 0.5, 0, 15, 0, 0.5, 0, 20, 0.8, 0.5, 0, 25, 0, 0.5, 0, 255, 0, 0.5, 0],
        "RGBPoints": [0, 1, 1, 1, 255, 1, 0.5, 0.2]
    })", "peak TF");
    return tf;
}

// Transparent below 100, a constant opacity from 150.
const TransferFunction& stepTf() {
    static const TransferFunction tf = parseTransferFunction(R"({
        "Points": [0, 0, 0.5, 0, 100, 0, 0.5, 0, 150, 0.3, 0.5, 0, 255, 0.3, 0.5, 0],
        "RGBPoints": [0, 1, 1, 1, 255, 1, 1, 1]
    })", "step TF");
    return tf;
}

PreparedVolume classified(Volume volume, const TransferFunction& tf) {
    PreparedVolume p;
    p.scalars = std::move(volume);
    ClassifyParams params;
    params.transferFunction = tf;
    p.classification = scalarClassification(p.scalars, params);
    return p;
}

Extents blocksOf(const BlockEACD& h, int oct, const Vec3i& voxel) {
    return decodeExtents(ExtentCode::Log16, h.code(oct, voxel));
}

std::size_t homogeneousBlocks(const BlockEACD& h, int oct) {
    std::size_t count = 0;
    for (int z = 0; z < h.blocks.z; ++z)
        for (int y = 0; y < h.blocks.y; ++y)
            for (int x = 0; x < h.blocks.x; ++x)
                count += (h.code(oct, Vec3i{x, y, z} * (1 << h.blockShift)) & kHomogeneousBlockBit) != 0;
    return count;
}

TEST(PipelineHierField, BlocksReachTheBorderThatCutsTheLastShort) {
    // 10 x 9 x 7 voxels: 3 x 3 x 2 blocks of 4, the last of each axis cut short by the border.
    const PreparedVolume p = classified(constantPhantom({10, 9, 7}, 0), stepTf());
    const BlockEACD h = buildHierarchicalEACD(p, {0, 0, true, true});
    EXPECT_EQ(h.blockShift, 2);
    EXPECT_EQ(h.blocks, (Vec3i{3, 3, 2}));
    EXPECT_EQ(h.octants(), kAllOctants);
    EXPECT_EQ(h.bytes(), 8u * 18 * 2);
    for (int oct = 0; oct < kOctants; ++oct) EXPECT_EQ(homogeneousBlocks(h, oct), 18u);
    // Toward +x+y+z from the first block: every block; from the last one: itself (the border follows).
    EXPECT_EQ(blocksOf(h, 0, {0, 0, 0}), (Extents{3, 3, 2}));
    EXPECT_EQ(blocksOf(h, 0, {9, 8, 6}), (Extents{1, 1, 1}));
    EXPECT_EQ(blocksOf(h, 7, {9, 8, 6}), (Extents{3, 3, 2}));
    EXPECT_EQ(blocksOf(h, 1, {5, 0, 0}), (Extents{2, 3, 2}));  // -x from the middle block
    // Blocks of 8: 2 x 2 x 1.
    const BlockEACD eight = buildHierarchicalEACD(p, {0, 0, true, true}, kAllOctants, 3);
    EXPECT_EQ(eight.blocks, (Vec3i{2, 2, 1}));
    EXPECT_EQ(blocksOf(eight, 0, {0, 0, 0}), (Extents{2, 2, 1}));
}

TEST(PipelineHierField, BlocksWhoseFootprintsReachAVisibleVoxelAreMixed) {
    Volume v = constantPhantom({16, 16, 16}, 0);
    v.values[linearIndex(v.grid.dims, 8, 8, 8)] = 200;
    const BlockEACD h = buildHierarchicalEACD(classified(std::move(v), stepTf()), {0, 0, true, true});
    // Voxel 8 lies in block 2 (voxels 8..11) and in the footprint of block 1 (voxels 3..8 with the trilinear margin):
    // blocks 1 and 2 on each axis are mixed.
    EXPECT_EQ(homogeneousBlocks(h, 0), 64u - 8u);
    EXPECT_EQ(h.code(0, {4, 4, 4}), 0);
    EXPECT_EQ(h.code(0, {11, 11, 11}), 0);
    EXPECT_NE(h.code(0, {12, 8, 8}) & kHomogeneousBlockBit, 0);
    // From block (0, 1, 1) toward +x the box stops before the mixed block 1: one block.
    EXPECT_EQ(blocksOf(h, 0, {0, 4, 4})[0], 1);
}

TEST(PipelineHierField, ANarrowPeakBetweenTwoTransparentValuesIsNeverLeapt) {
    // Voxels of 10 and 30 side by side, both transparent; an interpolated sample between them takes 20, the peak.
    Volume v = constantPhantom({24, 20, 16}, 10);
    for (std::size_t i = 0; i < v.values.size(); ++i)
        if (i / 4 % 2) v.values[i] = 30;
    const PreparedVolume p = classified(std::move(v), peakTf());
    for (bool trilinear : {false, true}) {
        const BlockEACD h = buildHierarchicalEACD(p, {0, 0, false, trilinear});
        EXPECT_EQ(homogeneousBlocks(h, 0), 0u) << trilinear;
    }
    // Rendered: the peak shows, and hier's image is the primitive caster's.
    PreparedVolume rendered = p;
    rendered.meta.segmentation = {0, 0, false, true};
    rendered.fields.hier = buildHierarchicalEACD(rendered, rendered.meta.segmentation);
    RenderSettings s;
    s.trilinear = true;
    s.shading = false;
    const Camera camera =
        Camera::fit(rendered.grid(), ViewParams{.azimuthDeg = 30, .elevationDeg = 20, .width = 32, .height = 32});
    const RenderResult primitive = renderCpu(rendered, camera, s);
    s.caster = Caster::Hier;
    const RenderResult hier = renderCpu(rendered, camera, s);
    EXPECT_GT(*std::max_element(primitive.image.rgba.begin(), primitive.image.rgba.end()), 0.1f);
    EXPECT_LT(maxAbsDifference(primitive.image, hier.image), 1e-6);
}

TEST(PipelineHierField, ShadedBlocksAreHomogeneousOnlyWhereTransparent) {
    // A constant visible volume: one classification throughout, but a span is shaded once, so with normals in use
    // only transparent blocks are leapt.
    const PreparedVolume p = classified(constantPhantom({12, 12, 12}, 200), stepTf());
    EXPECT_EQ(homogeneousBlocks(buildHierarchicalEACD(p, {0, 0, true, true}), 0), 0u);
    const BlockEACD unshaded = buildHierarchicalEACD(p, {0, 0, false, true});
    EXPECT_EQ(homogeneousBlocks(unshaded, 0), 27u);
    EXPECT_EQ(blocksOf(unshaded, 0, {0, 0, 0}), (Extents{3, 3, 3}));
}

TEST(PipelineHierField, OpacityThresholdJoinsBlocksWithinIt) {
    // A ramp of opacity along x: at T_o = 0 no visible block is alike; at T_o = 1 the whole volume is.
    const TransferFunction ramp = parseTransferFunction(
        R"({"Points": [0, 0, 0.5, 0, 255, 0.5, 0.5, 0], "RGBPoints": [0, 1, 1, 1, 255, 1, 1, 1]})", "ramp TF");
    const PreparedVolume p = classified(rampPhantom({32, 8, 8}, 0), ramp);
    EXPECT_EQ(homogeneousBlocks(buildHierarchicalEACD(p, {0, 0, false, true}), 0), 0u);
    const BlockEACD wide = buildHierarchicalEACD(p, {1, 0, false, true});
    EXPECT_EQ(homogeneousBlocks(wide, 0), 32u);
    EXPECT_EQ(blocksOf(wide, 0, {0, 0, 0}), (Extents{8, 2, 2}));
}

TEST(PipelineHierField, LabelMapsAndBadThresholdsAreRefused) {
    PreparedVolume p = classified(constantPhantom({8, 8, 8}, 0), stepTf());
    EXPECT_THROW(buildHierarchicalEACD(p, {-1, 0, true, true}), InputError);
    p.labels = LabelMap{};
    EXPECT_THROW(buildHierarchicalEACD(p, {0, 0, true, true}), InputError);
}

TEST(PipelineHierField, PreparedWithoutSegmentingAnyVoxel) {
    StagedPreparation staged(shellsPhantom({20, 18, 16}));
    PrepareOptions o;
    o.classify.transferFunction = stepTf();
    o.segmentation = {0, 0, true, true};
    o.fields = kFieldHier;
    o.keepRegions = false;
    o.octants = 1u << 3;
    const PreparedVolume& p = staged.prepare(o);
    EXPECT_EQ(staged.runs(PrepStage::Segment), 0);
    EXPECT_TRUE(p.regions.label.empty());
    EXPECT_EQ(p.fields.hier.octants(), 1u << 3);
    EXPECT_EQ(p.meta.segmentation, o.segmentation);
    const std::vector<StageTime>& last = staged.lastStages();
    ASSERT_FALSE(last.empty());
    EXPECT_EQ(last.back().stage, "hier");
    // Another threshold builds it again, still without segmenting.
    o.segmentation.opacityThreshold = 0.05;
    staged.prepare(o);
    EXPECT_EQ(staged.runs(PrepStage::Segment), 0);
    EXPECT_EQ(staged.runs(PrepStage::Fields), 2);
}

}  // namespace
}  // namespace vr
