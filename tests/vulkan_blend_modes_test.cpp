// The blends other than composite on the Vulkan casters (docs/ALGORITHMS.md section 11): the cases the CPU reference
// passes (tests/support/blend_cases.*), in float, and a volume split into bricks, which carries each ray's running
// value from brick to brick.
#include <gtest/gtest.h>

#include "core/errors.h"
#include "support/blend_cases.h"
#include "support/views.h"
#include "support/vulkan.h"

namespace vr {
namespace {

using test::reportValidated;

const test::RenderFn kVulkan = test::vulkanRender(16);
// Float classification and the float pairs of average; three views (a pipeline is compiled per variant).
constexpr test::BlendCaseOptions kDevice{1e-5, 3};

// At least two bricks along every axis, each image at most 24 texels along an axis.
VulkanRenderer& bricked() {
    static VulkanRenderer r(test::vulkanContext(), 32, ImageLimits{.maxDimension = 24, .minBricks = {2, 2, 2}});
    return r;
}

TEST(VulkanBlendModes, BlocksCasterEqualsPrimitive) {
    reportValidated("blocks = primitive", test::blocksEqualPrimitive(kVulkan, kDevice));
}

TEST(VulkanBlendModes, BlendsMatchBruteForce) {
    reportValidated("brute force", test::blendsMatchBruteForce(kVulkan, 0.02));
}

TEST(VulkanBlendModes, AxisMipIsColumnMaximum) {
    reportValidated("column maximum", test::axisMipIsColumnMaximum(kVulkan, kDevice));
}

TEST(VulkanBlendModes, GreyWindowIsLinearAndOpaque) {
    reportValidated("grey window", test::greyWindowIsLinear(kVulkan, kDevice));
}

TEST(VulkanBlendModes, OppositeViewsAreMirrorImages) {
    reportValidated("mirror images", test::oppositeViewsMirror(kVulkan, kDevice));
}

TEST(VulkanBlendModes, BrickedVolumeRendersTheWholeVolumesImage) {
    const test::BlendVolume& v = test::blendVolumes().front();
    for (Blend blend : {Blend::MIP, Blend::MinIP, Blend::Average})
        for (Caster caster : {Caster::Primitive, Caster::Blocks})
            for (const ViewParams& view : {test::orbitView(30, 20, 24, 20), test::orbitView(-140, -35, 20, 24)}) {
                const Camera camera = Camera::fit(v.prepared.grid(), view);
                const RenderSettings s = test::blendSettings(blend, caster, true, v.isoValue);
                const RenderResult whole = kVulkan(v.prepared, camera, s);
                const RenderResult split = bricked().render(v.prepared, camera, s);
                EXPECT_LE(maxAbsDifference(whole.image, split.image), 1e-5) << blendName(blend) << " " << casterName(caster);
                EXPECT_EQ(whole.samples, split.samples) << blendName(blend) << " " << casterName(caster);
            }
    // The iso-surface is refined between two samples, which one brick's images may not both hold.
    const Camera camera = Camera::fit(v.prepared.grid(), test::orbitView(0, 0, 8, 8));
    EXPECT_THROW(bricked().render(v.prepared, camera, test::blendSettings(Blend::Iso, Caster::Blocks, true, v.isoValue)),
                 InputError);
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
