// The stiff numerics of docs/ALGORITHMS.md section 6 on the Vulkan casters (positions and opacity in float in the
// shaders): the same cases as cpu_stiff_spans_test, against the same double-precision answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "shaders/transfer_lookup.h"
#include "support/vulkan.h"

namespace vr {
namespace {

using test::reportValidated;

const test::RenderFn kVulkan = test::vulkanRender(32);

// The extinction a nearest sample of this scalar takes (shaders/transfer_lookup.h, as the casters classify it).
double sigmaOf(const PreparedVolume& p, double scalar) {
    const TransferTable& table = p.classification.table;
    const double t = device::tableCoordinate(scalar, table.lo, 1 / table.step, double(table.size() - 1));
    const std::size_t i = std::size_t(t), j = std::min(i + 1, table.size() - 1);
    return device::interpolate(table.sigma[i], table.sigma[j], t - double(i));
}

// llvmpipe ends a shader after 65535 loop iterations in all, about 3,000 fetches of a ray that checks its leaps
// (a loop per fetch): there, rays asking primitive or PC stepping for more samples are left to the CPU test (and
// to the test below); a hardware device runs them all.
test::CaseOptions options() {
    test::CaseOptions o;
    o.floatLattice = true;
    if (test::vulkanContext().info().name.find("llvmpipe") != std::string::npos) o.maxSteppedSamples = 2000;
    return o;
}

TEST(VulkanStiffSpans, RenderedSpanOpacityOverTheOpacityAndLengthGrid) {
    reportValidated("span opacity grid", test::spanOpacityGrid(kVulkan, options()));
}

TEST(VulkanStiffSpans, ThinSlabsMatchTheLatticeSum) {
    reportValidated("thin slabs", test::thinSlabsAgainstTheLatticeSum(kVulkan, options()));
}

TEST(VulkanStiffSpans, HugeRegionMatchesTheClosedForm) {
    reportValidated("huge region", test::hugeRegionAgainstTheClosedForm(kVulkan, options()));
}

// 70,400 samples stepped one by one along one ray. Where a driver ends loops on its own (llvmpipe) the render must
// fail or finish, never return a ray cut short (it used to: 3,449 samples and a wrong image).
TEST(VulkanStiffSpans, RayLongerThanTheDriverLoopLimitIsAnErrorOrComplete) {
    const int m = 1100;
    const PreparedVolume p = test::syntheticPrepared({{1, 1, m}, {1, 1, 1}, {0, 0, 0}}, 1.0, [](const Vec3i&) {
        return test::VoxelClass{1e-4, {1, 1, 1}};
    });
    const Camera cam = test::orthoCamera({0.5, 0.5, m + 1.0}, {0, 0, -1}, {1, 0, 0}, 1, 1, 0.5);
    RenderSettings s;
    s.shading = false;
    s.stepVoxels = 1.0 / 64;
    s.ert = 1;
    int cutShort = 0;
    for (Caster c : {Caster::Primitive, Caster::PC}) {
        s.caster = c;
        try {
            const RenderResult r = kVulkan(p, cam, s);
            EXPECT_EQ(r.samples[0], uint64_t(64 * m)) << casterName(c);
            EXPECT_NEAR(r.image.pixel(0, 0)[3], -std::expm1(-sigmaOf(p, p.scalars.values[0]) * m), 1e-5);
        } catch (const std::runtime_error& e) {
            ++cutShort;
            EXPECT_NE(std::string(e.what()).find("ended the shader's loops"), std::string::npos) << e.what();
        }
    }
    // llvmpipe ends a shader after 65,535 loop iterations in all, so neither caster (the PC ball is one voxel
    // here) can finish there: the limit's detection is exercised.
    if (options().maxSteppedSamples < 64 * m) {
        EXPECT_GT(cutShort, 0);
    }
    // A leaping caster crosses the same region in a few fetches and finishes on any driver.
    s.caster = Caster::EACD;
    EXPECT_EQ(kVulkan(p, cam, s).samples[0], uint64_t(64 * m));
}

TEST(VulkanStiffSpans, EarlyTerminationHitExactly) {
    reportValidated("ert hit exactly", test::earlyTerminationHitExactly(kVulkan));
}

}  // namespace
}  // namespace vr
