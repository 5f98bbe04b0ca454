// The validation layer's messenger, which every Vulkan test relies on when it checks that the layer reported no
// error (tests/support/vulkan.h: expectNoValidationErrors).
#include <gtest/gtest.h>

#include <numeric>
#include <set>

#include "core/errors.h"
#include "render/render_checks.h"
#include "shaders/device_contract.h"
#include "shaders/embedded_shaders.h"
#include "support/render_cases.h"
#include "support/views.h"
#include "volrender/vulkan/vulkan_context.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {
namespace {

// The messenger the other tests rely on ("no validation errors") does record errors: a zero-sized buffer is one.
TEST(VulkanValidation, MessengerRecordsErrors) {
    VulkanContext ctx(VulkanOptions{-1, true});
    ASSERT_TRUE(ctx.validationEnabled()) << "VK_LAYER_KHRONOS_validation is not installed";
    EXPECT_TRUE(ctx.validationErrors().empty());
    try {
        vk::raii::Buffer buffer(ctx.device(), vk::BufferCreateInfo({}, 0, vk::BufferUsageFlagBits::eStorageBuffer));
    } catch (const vk::SystemError&) {
        // The driver may refuse it too; the layer has spoken first.
    }
    EXPECT_FALSE(ctx.validationErrors().empty());
}

// The capabilities a SPIR-V module declares (OpCapability: opcode 17, one operand), walking its instructions.
std::set<uint32_t> capabilities(const std::vector<uint32_t>& spirv) {
    std::set<uint32_t> found;
    for (std::size_t i = 5; i < spirv.size(); i += std::max(1u, spirv[i] >> 16))
        if ((spirv[i] & 0xffff) == 17) found.insert(spirv[i + 1]);
    return found;
}

// The casters compute in float and 32-bit integers: their SPIR-V declares neither Float64 (capability 10) nor
// Int64 (11), and every caster, projection and brick layout creates its pipeline and renders on a context that
// enables neither shaderFloat64 nor shaderInt64 (no context does) without a validation error, which the layer
// reports for a shader using a feature the device did not enable.
TEST(VulkanValidation, CastersNeedNeitherFloat64NorInt64) {
    for (int caster = 0; caster <= device::kHier; ++caster)
        for (int blend = 0; blend <= device::kBlendIso; ++blend)
            for (const bool plain : {false, true}) {
                const std::vector<uint32_t>* module = casterModule(caster, blend, plain);
                if (!module) continue;
                const std::set<uint32_t> used = capabilities(*module);
                EXPECT_FALSE(used.empty());
                EXPECT_EQ(used.count(10), 0u) << "caster " << caster << ", blend " << blend << " declares Float64";
                EXPECT_EQ(used.count(11), 0u) << "caster " << caster << ", blend " << blend << " declares Int64";
            }

    VulkanContext ctx(VulkanOptions{-1, true});
    ASSERT_TRUE(ctx.validationEnabled()) << "VK_LAYER_KHRONOS_validation is not installed";
    const PreparedVolume p = test::syntheticPrepared({{6, 5, 7}, {1, 1, 1}, {0, 0, 0}}, 1.0, [](const Vec3i& v) {
        return test::VoxelClass{v.z < 3 ? 0.0 : 0.1 * (v.x % 3), {0.2, 0.5, 0.9}};
    });
    RenderSettings s;
    s.shading = false;
    // An orthographic view of one brick, then a perspective view of bricks of at most 5 texels a side (a core of
    // one voxel and its margin of two).
    const std::pair<Projection, ImageLimits> variants[] = {{Projection::Orthographic, ImageLimits{}},
                                                           {Projection::Perspective, ImageLimits{5, 0, false}}};
    for (const auto& [projection, limits] : variants) {
        VulkanRenderer renderer(ctx, 16, limits);
        const Camera camera = Camera::fit(p.grid(), test::orbitView(30, 20, 20, 18, projection));
        for (const Caster c : test::kCasters) {
            s.caster = c;
            const RenderResult r = renderer.render(p, camera, s);
            EXPECT_GT(std::accumulate(r.samples.begin(), r.samples.end(), uint64_t(0)), 0u) << casterName(c);
        }
    }
    const auto errors = ctx.validationErrors();
    EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, first: " << errors.front();
}

// Each caster is one module per blend: every pair the renderer accepts has its module, and only those; composite
// also a plain one.
TEST(VulkanValidation, EveryAcceptedCasterAndBlendHasItsModule) {
    const Caster casters[] = {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD, Caster::Blocks, Caster::Hier};
    const Blend blends[] = {Blend::Composite, Blend::MIP, Blend::MinIP, Blend::Average, Blend::Iso};
    int accepted = 0;
    for (const Caster c : casters)
        for (const Blend b : blends) {
            RenderSettings s;
            s.caster = c;
            s.blend = b;
            s.isoValue = 0.5;
            bool accepts = true;
            try {
                checkBlend(s);
            } catch (const InputError&) {
                accepts = false;
            }
            accepted += accepts;
            EXPECT_EQ(casterModule(int(c), int(b), false) != nullptr, accepts) << casterName(c) << " " << blendName(b);
            EXPECT_EQ(casterModule(int(c), int(b), true) != nullptr, accepts && b == Blend::Composite)
                << casterName(c) << " " << blendName(b) << ", plain";
        }
    EXPECT_EQ(accepted, 13);
}

}  // namespace
}  // namespace vr
