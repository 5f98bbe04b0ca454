// The blends other than composite on the Vulkan casters (docs/ALGORITHMS.md section 11): the cases the CPU reference
// passes (tests/support/blend_cases.*), in float, and a volume split into bricks, which carries each ray's running
// value from brick to brick.
#include <gtest/gtest.h>

#include <numeric>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/transfer_choice.h"
#include "support/blend_cases.h"
#include "support/prepare.h"
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

// A window whose grey no longer changes above the engine's metal (200, 255) and below its air (0): MIP and MinIP end
// a ray once its value is there (render/flat_table_ends.h). The image is the CPU reference's, which never ends a ray
// early, and the rays take fewer iterations than under a window that changes over every value.
TEST(VulkanBlendModes, RaysEndWhereTheWindowNoLongerChanges) {
    const Volume volume = enginePhantom({31, 27, 23});
    const auto prepared = [&](double window, double level) {
        const TransferFunction tf = windowLevelTransferFunction(window, level, nullptr);
        return test::prepareVolume(volume, tf, {0, 0, false, false}, 0);
    };
    const PreparedVolume flat = prepared(100, 100), ramp = prepared(1000, 100);  // grey 50..150 and -400..600
    const auto total = [](const std::vector<uint32_t>& v) { return std::accumulate(v.begin(), v.end(), 0.0); };
    for (Blend blend : {Blend::MIP, Blend::MinIP})
        for (Caster caster : {Caster::Primitive, Caster::Blocks})
            for (bool trilinear : {false, true}) {
                const std::string what = std::string(blendName(blend)) + " " + std::string(casterName(caster)) +
                                         (trilinear ? " trilinear" : "");
                const Camera camera = Camera::fit(flat.grid(), test::orbitView(30, 20, 24, 20));
                RenderSettings s = test::blendSettings(blend, caster, trilinear, 0);
                s.opaqueValues = true;
                const RenderResult ended = kVulkan(flat, camera, s), reference = test::kCpuReference(flat, camera, s);
                EXPECT_LE(maxAbsDifference(ended.image, reference.image), 1e-5) << what;
                EXPECT_EQ(ended.samples, reference.samples) << what;  // an ended ray represents the rest of its samples
                EXPECT_LT(total(ended.iterations), 0.8 * total(kVulkan(ramp, camera, s).iterations)) << what;
            }
}

// Noisy air under a transfer function transparent there, whose colour still ramps (as CT presets' do), around a
// cube of metal: MIP starts its maximum where the table stops changing what it shows (render/flat_table_ends.h), so
// the blocks caster leaps the air whole from the start, where the noise would raise a maximum from -inf block after
// block. MinIP likewise, with the air above the cube's value and transparent at the table's top. The image is the
// CPU reference's primitive caster's, which starts at -inf (+inf). The CPU reference's blocks caster starts as the
// device's does, so that auto's probe (render/ray_probe.h) counts as few iterations.
TEST(VulkanBlendModes, TransparentNoiseIsLeaptFromTheStart) {
    struct Case {
        Blend blend;
        int noiseLow, noiseHigh;
        float cube;
        std::vector<TransferFunction::OpacityPoint> opacity;
    };
    const Case cases[] = {{Blend::MIP, 0, 60, 200, {{0, 0}, {100, 0}, {255, 1}}},
                          {Blend::MinIP, 195, 255, 20, {{0, 1}, {150, 0}, {255, 0}}}};
    const auto total = [](const std::vector<uint32_t>& v) { return std::accumulate(v.begin(), v.end(), 0.0); };
    for (const Case& c : cases) {
        Volume volume = noisePhantom({32, 32, 32}, 7, c.noiseLow, c.noiseHigh);
        for (int z = 12; z < 20; ++z)
            for (int y = 12; y < 20; ++y)
                for (int x = 12; x < 20; ++x) volume.values[linearIndex(volume.grid.dims, x, y, z)] = c.cube;
        TransferFunction tf;
        tf.opacity = c.opacity;
        tf.colour = {{0, 0, 0, 0}, {255, 1, 1, 1}};
        const PreparedVolume prepared = test::prepareVolume(volume, tf, {0, 0, false, false}, 0);
        for (bool trilinear : {false, true}) {
            const std::string what = std::string(blendName(c.blend)) + (trilinear ? " trilinear" : " nearest");
            const Camera camera = Camera::fit(prepared.grid(), test::orbitView(30, 20, 24, 20));
            const RenderSettings blocks = test::blendSettings(c.blend, Caster::Blocks, trilinear, 0);
            const RenderSettings primitive = test::blendSettings(c.blend, Caster::Primitive, trilinear, 0);
            const RenderResult leapt = kVulkan(prepared, camera, blocks);
            const RenderResult reference = test::kCpuReference(prepared, camera, primitive);
            EXPECT_LE(maxAbsDifference(leapt.image, reference.image), 1e-5) << what;
            EXPECT_EQ(leapt.samples, reference.samples) << what;
            EXPECT_LT(total(leapt.iterations), 0.25 * total(kVulkan(prepared, camera, primitive).iterations)) << what;
            const RenderResult cpuLeapt = test::kCpuReference(prepared, camera, blocks);
            EXPECT_LT(total(cpuLeapt.iterations), 0.25 * total(reference.iterations)) << what;
        }
    }
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
                EXPECT_LE(maxAbsDifference(whole.image, split.image), 1e-5)
                    << blendName(blend) << " " << casterName(caster);
                EXPECT_EQ(whole.samples, split.samples) << blendName(blend) << " " << casterName(caster);
            }
    // The iso-surface is refined between two samples, which one brick's images may not both hold.
    const Camera camera = Camera::fit(v.prepared.grid(), test::orbitView(0, 0, 8, 8));
    EXPECT_THROW(
        bricked().render(v.prepared, camera, test::blendSettings(Blend::Iso, Caster::Blocks, true, v.isoValue)),
        InputError);
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
