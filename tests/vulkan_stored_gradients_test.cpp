// Shading by stored gradients on the device: the casters against the CPU reference shading by the same codes,
// leaping casters against primitive at thresholds 0, and what is uploaded for them.
#include <gtest/gtest.h>

#include <stdexcept>

#include "datasets/phantoms.h"
#include "render/cpu_renderer.h"
#include "render/view_octants.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/volumes.h"
#include "support/vulkan.h"

namespace vr {
namespace {

VulkanRenderer& renderer() { return test::vulkanRenderer(40); }

RenderSettings storedSettings(Caster c, bool trilinear) {
    RenderSettings s = test::renderSettings(c, true, trilinear);
    s.gradients = Gradients::Stored;
    return s;
}

std::vector<Camera> cameras(const GridGeometry& grid) {
    return {Camera::fit(grid, test::orbitView(0, 0, 64, 48, Projection::Orthographic)),
            Camera::fit(grid, test::orbitView(37, 23, 64, 48, Projection::Orthographic)),
            Camera::fit(grid, test::orbitView(30, -20, 64, 48, Projection::Perspective))};
}

PreparedVolume headsq(double to, double ta, bool trilinear) {
    const Volume v = test::centralBlock(test::loadDataset("vtk_headsq_ct"), 40);
    return test::prepareVolume(v, test::datasetTransferFunction("vtk_headsq_ct.tf.json"), {to, ta, true, trilinear});
}

TEST(VulkanStoredGradients, CastersMatchCpuReference) {
    for (bool trilinear : {false, true}) {
        const PreparedVolume p = headsq(0.02, 10, trilinear);
        for (const Camera& camera : cameras(p.grid()))
            for (Caster c : test::kCasters) {
                const RenderSettings s = storedSettings(c, trilinear);
                SCOPED_TRACE(std::string(casterName(c)) + (trilinear ? " trilinear" : " nearest"));
                test::expectNearCpuReference(renderer().render(p, camera, s), renderCpu(p, camera, s));
            }
    }
    test::expectNoValidationErrors();
}

TEST(VulkanStoredGradients, LeapingCastersEqualPrimitiveAtZeroThresholds) {
    for (bool trilinear : {false, true}) {
        const PreparedVolume p = headsq(0, 0, trilinear);
        for (const Camera& camera : cameras(p.grid())) {
            const RenderResult primitive = renderer().render(p, camera, storedSettings(Caster::Primitive, trilinear));
            for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD}) {
                SCOPED_TRACE(std::string(casterName(c)) + (trilinear ? " trilinear" : " nearest"));
                EXPECT_LT(maxAbsDifference(renderer().render(p, camera, storedSettings(c, trilinear)).image,
                                           primitive.image),
                          1e-4);
            }
        }
    }
    test::expectNoValidationErrors();
}

TEST(VulkanStoredGradients, UploadedOnlyWhenAskedForAndRequiredToShadeBy) {
    const PreparedVolume p = headsq(0.02, 10, true);
    const Camera camera = cameras(p.grid()).front();
    const GpuVolume without = renderer().upload(p, {{Caster::Primitive}, viewOctants(camera)});
    EXPECT_EQ(test::bytesByName(without.uploads()).count("gradients"), 0u);
    EXPECT_THROW(renderer().render(without, camera, storedSettings(Caster::Primitive, true)), std::invalid_argument);
    const GpuVolume with = renderer().upload(p, {{Caster::Primitive}, viewOctants(camera), true});
    EXPECT_EQ(test::bytesByName(with.uploads()).at("gradients"), 4 * p.grid().voxels());
    // Unshaded renders read no gradients: the on-the-fly and stored variants are one.
    RenderSettings unshaded = storedSettings(Caster::Primitive, true);
    unshaded.shading = false;
    EXPECT_NO_THROW(renderer().render(with, camera, unshaded));
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
