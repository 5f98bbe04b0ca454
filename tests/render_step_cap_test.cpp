// A step so small that a ray across the volume takes more samples than the iteration cap is a user's mistake, not
// a caster's bug: the renderers refuse it before casting, naming --step and the smallest step that fits, instead of
// reporting the cap's "a bug" error after the primitive caster runs into it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.h"
#include "support/render_cases.h"
#include "render/cpu_renderer.h"
#include "render/render_checks.h"

namespace vr {
namespace {

// 12 x 10 x 8 voxels of spacing (1, 1, 2): a diagonal of sqrt(12^2 + 10^2 + 16^2) = 22.36 smallest spacings.
const GridGeometry kGrid{{12, 10, 8}, {1, 1, 2}, {0, 0, 0}};

RenderSettings withStep(double step) {
    RenderSettings s;
    s.shading = false;
    s.stepVoxels = step;
    return s;
}

std::string refusal(const RenderSettings& s) {
    try {
        requireSamplesWithinCap(kGrid, s);
    } catch (const InputError& e) {
        return e.what();
    }
    return {};
}

TEST(RenderStepCap, StepsBeyondTheIterationCapAreRefusedNamingTheFlag) {
    const double diagonal = length(kGrid.extent());
    const double cap = double(RenderSettings{}.maxIterationsPerRay);
    for (double step : {1e-9, 1e-7, 1e-300}) {
        const std::string message = refusal(withStep(step));
        EXPECT_EQ(message.rfind("--step ", 0), 0u) << message;
        EXPECT_NE(message.find("iteration cap of 16777216"), std::string::npos) << message;
        EXPECT_NE(message.find("smallest step it allows is 1.33e-06 voxels"), std::string::npos) << message;
    }
    // The boundary: a lattice of exactly the cap's samples fits, one more does not.
    EXPECT_EQ(refusal(withStep(diagonal / (cap - 0.5))), "");
    EXPECT_NE(refusal(withStep(diagonal / (cap + 1.5))), "");
    // A larger cap allows a finer step.
    RenderSettings raised = withStep(1e-7);
    raised.maxIterationsPerRay = 1LL << 30;
    EXPECT_EQ(refusal(raised), "");
    // A cap lowered to catch runaway casters does not limit the step: the default cap still applies.
    RenderSettings lowered = withStep(1e-3);
    lowered.maxIterationsPerRay = 5;
    EXPECT_EQ(refusal(lowered), "");
}

TEST(RenderStepCap, TheRendererRefusesBeforeCasting) {
    const PreparedVolume p =
        test::syntheticPrepared(kGrid, 1.0, [](const Vec3i&) { return test::VoxelClass{0, {1, 1, 1}}; });
    const Camera cam = Camera::fit(kGrid, test::orbitView(0, 0, 4, 4));
    try {
        renderCpu(p, cam, withStep(1e-9));
        ADD_FAILURE() << "a step of 1e-9 voxels rendered";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--step 1e-09"), std::string::npos) << e.what();
    }
    // An ordinary step over the same all-transparent volume renders (every ray takes its full lattice).
    EXPECT_NO_THROW(renderCpu(p, cam, withStep(0.5)));
}

}  // namespace
}  // namespace vr
