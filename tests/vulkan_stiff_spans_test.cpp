// The stiff numerics of ALGORITHMS.md section 6 on the Vulkan casters (positions and opacity in double in the
// shaders): the same cases as cpu_stiff_spans_test, against the same double-precision answers.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/render_cases.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {
namespace {

VulkanContext& context() {
    static VulkanContext ctx(VulkanOptions{-1, true});  // validation on
    return ctx;
}

const test::RenderFn kVulkan = [](const PreparedVolume& p, const Camera& c, const RenderSettings& s) {
    static VulkanRenderer renderer(context(), 32);
    return renderer.render(p, c, s);
};

void report(const char* family, const test::CaseCount& n) {
    std::printf("%s: %d renders, %d rays, %d of them hitting the volume\n", family, n.renders, n.rays, n.hits);
    const auto errors = context().validationErrors();
    EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, first: " << errors.front();
}

// Primitive and PC step 1e7 samples one by one in a one-voxel volume: too slow for a software device, so the
// 1e7-sample spans are checked with ACD and EACD (one fetch each) here and with every caster on the CPU.
TEST(VulkanStiffSpans, RenderedSpanOpacityOverTheOpacityAndLengthGrid) {
    test::CaseOptions options;
    options.primitiveTenMillion = false;
    report("span opacity grid", test::spanOpacityGrid(kVulkan, options));
}

TEST(VulkanStiffSpans, ThinSlabsMatchTheLatticeSum) {
    report("thin slabs", test::thinSlabsAgainstTheLatticeSum(kVulkan));
}

TEST(VulkanStiffSpans, HugeRegionMatchesTheClosedForm) {
    report("huge region", test::hugeRegionAgainstTheClosedForm(kVulkan));
}

TEST(VulkanStiffSpans, EarlyTerminationHitExactly) {
    report("ert hit exactly", test::earlyTerminationHitExactly(kVulkan));
}

}  // namespace
}  // namespace vr
