// Clipping on the device (shaders/ray_setup.glsl with shaders/clip_planes.h): for every clipping of
// tests/support/views.cpp the leaping casters render the primitive caster's image (the iso-surface's blocks caster
// too), every caster matches the CPU reference, and so does a volume split into bricks, whose rays start and end in
// different bricks.
#include <gtest/gtest.h>

#include "datasets/phantoms.h"
#include "support/blend_cases.h"
#include "render/cpu_renderer.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/volumes.h"
#include "support/vulkan.h"

namespace vr {
namespace {

void expectClippedRendersAgree(const std::string& name, const PreparedVolume& p, VulkanRenderer& renderer) {
    for (const ViewParams& view : {test::orbitView(0, 0, 48, 40), test::orbitView(37, 23, 48, 40),
                                   test::orbitView(-130, -50, 48, 40, Projection::Perspective)}) {
        const Camera cam = Camera::fit(p.grid(), view);
        for (const test::Clipping& c : test::clippings(p.grid())) {
            SCOPED_TRACE(name + ", " + c.name + ", az " + std::to_string(view.azimuthDeg));
            RenderSettings s = test::renderSettings(Caster::Primitive);
            c.applyTo(s);
            const RenderResult primitive = renderer.render(p, cam, s);
            test::expectNearCpuReference(primitive, renderCpu(p, cam, s));
            for (Caster caster : {Caster::PC, Caster::ACD, Caster::EACD}) {
                s.caster = caster;
                const RenderResult r = renderer.render(p, cam, s);
                EXPECT_LT(maxAbsDifference(r.image, primitive.image), 1e-4) << casterName(caster);
                test::expectNearCpuReference(r, renderCpu(p, cam, s));
            }
        }
    }
}

TEST(VulkanClipping, LeapingCastersEqualPrimitiveAndMatchTheCpuReference) {
    const PreparedVolume shells = test::prepareVolume(shellsPhantom({36, 36, 30}, {1, 1, 1.5}),
                                                      test::datasetTransferFunction("cranium_ct.tf.json"),
                                                      {0, 0, true, false});
    expectClippedRendersAgree("shells", shells, test::vulkanRenderer(40));
    const test::DatasetEntry head = test::rawDataset("vtk_headsq_ct");
    const PreparedVolume headBlock = test::prepareVolume(test::centralBlock(test::loadDataset(head), 40),
                                                         test::datasetTransferFunction(head.tf), {0, 0, true, false});
    expectClippedRendersAgree(head.file, headBlock, test::vulkanRenderer(40));
    test::expectNoValidationErrors();
}

// The iso-surface under every clipping: the blocks caster finds the primitive caster's surface, and both match the
// CPU reference.
TEST(VulkanClipping, IsoSurfaceBlocksEqualPrimitive) {
    VulkanRenderer& renderer = test::vulkanRenderer(40);
    for (const test::BlendVolume& v : test::blendVolumes()) {
        const Camera cam = Camera::fit(v.prepared.grid(), test::orbitView(37, 23, 48, 40));
        RenderSettings s = test::blendSettings(Blend::Iso, Caster::Primitive, true, v.isoValue);
        for (const test::Clipping& c : test::clippings(v.prepared.grid())) {
            SCOPED_TRACE(v.name + ", " + c.name);
            c.applyTo(s);
            s.caster = Caster::Primitive;
            const RenderResult primitive = renderer.render(v.prepared, cam, s);
            test::expectNearCpuReference(primitive, renderCpu(v.prepared, cam, s));
            s.caster = Caster::Blocks;
            EXPECT_LT(maxAbsDifference(renderer.render(v.prepared, cam, s).image, primitive.image), 1e-4);
        }
    }
    test::expectNoValidationErrors();
}

TEST(VulkanClipping, BrickedVolumes) {
    // At least three bricks along every axis, as in tests/vulkan_uploads_test.cpp.
    static VulkanRenderer bricked(test::vulkanContext(), 32, ImageLimits{.maxDimension = 40, .minBricks = {3, 3, 3}});
    const PreparedVolume engine = test::prepareVolume(
        enginePhantom({40, 32, 24}), test::datasetTransferFunction("mri.tf.json"), {0, 0, true, false});
    expectClippedRendersAgree("engine in bricks", engine, bricked);
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
