// Extreme geometry on the Vulkan casters: the cases of cpu_extreme_geometry_test, plus volumes larger than the
// device's 3D image limit, which render in bricks as the CPU reference renders them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "render/cpu_renderer.h"
#include "support/vulkan.h"

namespace vr {
namespace {

using test::reportValidated;

VulkanRenderer& renderer() { return test::vulkanRenderer(32); }
const test::RenderFn kVulkan = test::vulkanRender(32);

TEST(VulkanExtremeGeometry, CastersEqualPrimitiveOnEveryShapeContentAndView) {
    reportValidated("extreme geometry", test::extremeGeometry(kVulkan));
}

TEST(VulkanExtremeGeometry, TransparentOpaqueAndRegionsBeyondTheCap) {
    reportValidated("transparent / opaque / capped", test::transparentOpaqueAndCappedRegions(kVulkan));
}

TEST(VulkanExtremeGeometry, IterationCapIsAnError) {
    reportValidated("iteration cap", test::iterationCapIsAnError(kVulkan));
}

// One voxel longer than the device's largest 3D image: split into bricks, never a driver crash or a silently
// clipped image. A volume that fits once but not with two octants stacked along z (ACD, a view needing two
// octants) is split the same way.
TEST(VulkanExtremeGeometry, VolumeBeyondTheDeviceLimitRendersInBricks) {
    const int limit = int(test::vulkanContext().physicalDevice().getProperties().limits.maxImageDimension3D);
    auto expectBricks = [&](const GridGeometry& grid, const Camera& cam, Caster caster, const std::string& what) {
        const PreparedVolume p = test::syntheticPrepared(grid, 1.0, [](const Vec3i&) {
            return test::VoxelClass{0.1, {1, 1, 1}};
        });
        RenderSettings s;
        s.shading = false;
        s.caster = caster;
        const RenderResult gpu = renderer().render(p, cam, s);
        const RenderResult cpu = renderCpu(p, cam, s);
        EXPECT_LT(maxAbsDifference(gpu.image, cpu.image), 1e-4) << what;
        EXPECT_EQ(gpu.samples, cpu.samples) << what;
        int bricks = 0;
        for (const UploadedResource& u : renderer().lastUploads()) bricks = std::max(bricks, u.brick + 1);
        EXPECT_GE(bricks, 2) << what;
    };
    const GridGeometry tooLong{{1, 1, limit + 1}, {1, 1, 1}, {0, 0, 0}};
    const Camera side = test::orthoCamera({-1, 0.5, limit / 2.0}, {1, 0, 0}, {0, 0, 1}, 3, 1, 0.5);
    expectBricks(tooLong, side, Caster::Primitive, "1x1x(limit+1)");
    const GridGeometry half{{2, 1, limit / 2 + 1}, {1, 1, 1}, {0, 0, 0}};
    // Two rays, one along +x and one along -x of the same perspective view: octants 0 and 1 both needed.
    const Camera both = test::perspectiveCamera({1, 0.5, limit / 4.0}, {0, 0, 1}, {1, 0, 0}, 2, 1, 90);
    expectBricks(half, both, Caster::ACD, "two stacked octants of 2x1x(limit/2+1)");
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
