// Jitter (docs/ALGORITHMS.md section 1): each ray's lattice starts a per-pixel fraction of a step late. The fraction
// is spread over [0, 1), the same on every run, and every caster still samples one lattice per ray, so the leaping
// casters render the jittered primitive image at thresholds 0.
#include <gtest/gtest.h>

#include <set>

#include "datasets/phantoms.h"
#include "render/cpu_renderer.h"
#include "render/ray_setup.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/views.h"

namespace vr {
namespace {

TEST(RenderJitter, FractionsSpreadOverAStep) {
    std::set<double> seen;
    double sum = 0;
    int below = 0;
    for (device::uint y = 0; y < 64; ++y)
        for (device::uint x = 0; x < 64; ++x) {
            const double f = device::jitterFraction(x, y);
            ASSERT_GE(f, 0);
            ASSERT_LT(f, 1);
            EXPECT_EQ(f, double(float(f)));  // exact in float: the casters start at the same fraction
            seen.insert(f);
            sum += f;
            below += f < 0.25;
        }
    EXPECT_GT(seen.size(), 4000u);  // neighbours differ
    EXPECT_NEAR(sum / 4096, 0.5, 0.02);
    EXPECT_NEAR(below / 4096.0, 0.25, 0.03);
}

TEST(RenderJitter, StartsLateByTheFractionAndKeepsTheExit) {
    const RayInterval iv{2, 10};
    const RayInterval j = jitteredInterval(iv, 0.5, 0.75);
    EXPECT_EQ(j.tEntry, 2.375);
    EXPECT_EQ(j.tExit, 10);
    EXPECT_TRUE(jitteredInterval({2, 2.1}, 0.5, 0.5).empty());  // the start passed the exit: no sample
    EXPECT_TRUE(jitteredInterval({0, 0}, 0.5, 0.5).empty());
}

TEST(RenderJitter, LeapingCastersEqualJitteredPrimitive) {
    const Volume v = shellsPhantom({32, 30, 24}, {1, 1, 1.5});
    const TransferFunction tf = test::datasetTransferFunction("cranium_ct.tf.json");
    for (bool trilinear : {false, true}) {
        const PreparedVolume p = test::prepareVolume(v, tf, {0, 0, true, trilinear});
        const Camera camera = Camera::fit(p.grid(), test::orbitView(31, 17, 40, 40));
        RenderSettings s = test::renderSettings(Caster::Primitive, true, trilinear);
        const RenderResult plain = renderCpu(p, camera, s);
        s.jitter = true;
        const RenderResult primitive = renderCpu(p, camera, s);
        EXPECT_GT(maxAbsDifference(plain.image, primitive.image), 1e-3) << "jitter changed nothing";
        EXPECT_EQ(maxAbsDifference(renderCpu(p, camera, s).image, primitive.image), 0) << "not the same every run";
        for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD, Caster::Hier}) {
            s.caster = c;
            EXPECT_LT(maxAbsDifference(renderCpu(p, camera, s).image, primitive.image), 1e-6)
                << casterName(c) << (trilinear ? " trilinear" : " nearest");
        }
    }
}

}  // namespace
}  // namespace vr
