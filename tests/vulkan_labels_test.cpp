// Label maps and jitter on the Vulkan casters (docs/ALGORITHMS.md sections 1 and 2): the CPU reference's image, the
// leaping casters the primitive one's at thresholds 0, labels in 8 and 16 bits, whole and in bricks.
#include <gtest/gtest.h>

#include "datasets/phantoms.h"
#include "render/cpu_renderer.h"
#include "render/view_octants.h"
#include "support/label_maps.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/views.h"
#include "support/volumes.h"
#include "support/vulkan.h"

namespace vr {
namespace {

using test::expectNoValidationErrors;

VulkanRenderer& renderer() { return test::vulkanRenderer(24); }

struct Labelled {
    Volume volume;
    TransferFunction tf;
    LabelMap labels;
};

// A CT block with soft tissue (1) and bone (2) labelled; `wide`: bone as label 300, the labels then in 16 bits.
Labelled headCt(bool wide) {
    const test::DatasetEntry row = test::rawDataset("vtk_headsq_ct");
    Labelled l{test::centralBlock(test::loadDataset(row), 32), test::datasetTransferFunction(row.tf), {}};
    l.labels = test::thresholdLabels(l.volume, {1000, 2200});
    if (wide) {
        for (uint16_t& label : l.labels.label) label = label == 2 ? 300 : label;
        l.labels.rgba.resize(301, {0, 0, 0, 0});
        l.labels.rgba[300] = {250, 240, 200, 230};
        l.labels.type = ScalarType::UInt16;
    }
    return l;
}

PreparedVolume prepare(const Labelled& l, bool trilinear) {
    return test::prepareVolume(l.volume, l.tf, {0, 0, true, trilinear}, kRegionFields, l.labels);
}

TEST(VulkanLabels, MatchTheCpuReferenceAndLeapLikePrimitive) {
    for (bool wide : {false, true})
        for (bool trilinear : {false, true}) {
            const PreparedVolume p = prepare(headCt(wide), trilinear);
            // Oblique views: along an axis, samples fall on voxel faces, where float and double may round to
            // different voxels, and a label map's voxels differ sharply.
            const ViewParams v = trilinear ? test::orbitView(23, 11, 40, 32) : test::orbitView(-130, -50, 40, 32);
            const Camera camera = Camera::fit(p.grid(), v);
            RenderSettings s = test::renderSettings(Caster::Primitive, true, trilinear);
            SCOPED_TRACE(std::string(wide ? "uint16" : "uint8") + (trilinear ? " trilinear" : " nearest"));
            const RenderResult primitive = renderer().render(p, camera, s);
            test::expectNearCpuReference(primitive, renderCpu(p, camera, s));
            for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD}) {
                s.caster = c;
                EXPECT_LT(maxAbsDifference(renderer().render(p, camera, s).image, primitive.image), 1e-4)
                    << casterName(c);
            }
        }
    expectNoValidationErrors();
}

TEST(VulkanLabels, InBricksAsWhole) {
    const PreparedVolume p = prepare(headCt(false), true);
    static VulkanRenderer bricked(test::vulkanContext(), 24, ImageLimits{.maxDimension = 40, .minBricks = {3, 3, 3}});
    const Camera camera = Camera::fit(p.grid(), test::orbitView(37, 23, 40, 32));
    for (Caster c : {Caster::Primitive, Caster::EACD}) {
        const RenderSettings s = test::renderSettings(c, true, true);
        const GpuVolume split = bricked.upload(p, {{c}, viewOctants(camera)});
        ASSERT_GT(split.bricks().bricks().size(), 1u);
        EXPECT_LT(maxAbsDifference(bricked.render(split, camera, s).image, renderer().render(p, camera, s).image),
                  1e-4)
            << casterName(c);
    }
    expectNoValidationErrors();
}

TEST(VulkanLabels, JitterMatchesTheCpuReference) {
    const Volume v = shellsPhantom({32, 30, 24}, {1, 1, 1.5});
    const PreparedVolume p =
        test::prepareVolume(v, test::datasetTransferFunction("cranium_ct.tf.json"), {0, 0, true, true});
    const Camera camera = Camera::fit(p.grid(), test::orbitView(31, 17, 40, 32));
    RenderSettings s = test::renderSettings(Caster::Primitive, true, true);
    s.jitter = true;
    const RenderResult primitive = renderer().render(p, camera, s);
    test::expectNearCpuReference(primitive, renderCpu(p, camera, s));
    s.caster = Caster::EACD;
    EXPECT_LT(maxAbsDifference(renderer().render(p, camera, s).image, primitive.image), 1e-4);
    expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
