// Span integration on hand cases (docs/ALGORITHMS.md sections 5 and 6): span opacity from tiny to stiff, the
// accumulator, early termination and shading (render/span.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/classified_volume.h"
#include "render/span.h"

namespace vr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// 1 - exp(-x) in long double: a series where the subtraction would cancel.
long double closedFormOpacity(long double x) {
    if (x < 1e-3L) return x - x * x / 2 + x * x * x / 6 - x * x * x * x / 24 + x * x * x * x * x / 120;
    return 1 - std::exp(-x);
}

TEST(RenderSpanOpacity, MatchesTheClosedFormFromTinyToStiff) {
    for (double x = 1e-12; x <= 1e3; x *= 1.37) {
        const double got = spanOpacity(x, 1.0);
        const long double want = closedFormOpacity(x);
        EXPECT_NEAR(got, double(want), 4e-16 * double(want)) << "sigma L = " << x;
        // The same through sigma and L separately, as the renderer calls it.
        EXPECT_NEAR(spanOpacity(x / 250, 250), double(want), 6e-16 * double(want)) << "sigma L = " << x;
    }
    EXPECT_EQ(spanOpacity(0, 1e6), 0.0);
}

TEST(RenderSpanOpacity, TinyOpacitiesAddUpInsteadOfVanishing) {
    // 10,000 samples of alpha = 1e-8: in float, 1 - (1 - 1e-8f)^n is 0; the span gives ~1e-4.
    const double sigma = extinctionFromOpacity(1e-8, 1.0);
    const double a = spanOpacity(sigma, 10000);
    EXPECT_NEAR(a, double(1 - std::pow(1 - 1e-8L, 10000)), 2e-15);
    EXPECT_NEAR(a, 1e-4, 1e-8);
    EXPECT_EQ(1.0f - std::pow(1.0f - 1e-8f, 10000.0f), 0.0f);  // what the naive float formula gives
}

TEST(RenderSpanOpacity, OpaqueIsClampedFiniteAndSaturates) {
    const double sigma = extinctionFromOpacity(1.0, 0.5);
    ASSERT_TRUE(std::isfinite(sigma));
    const double a = spanOpacity(sigma, 0.5);
    EXPECT_GE(a, kMaxOpacityPerStep);
    EXPECT_LE(a, 1.0);
    EXPECT_EQ(float(a), 1.0f);                  // what the image stores
    EXPECT_EQ(spanOpacity(sigma, 1.0), 1.0);   // two reference steps are 1 exactly in double
    Accumulator acc;
    acc.composite({1, 1, 1}, a, sigma * 0.5);
    EXPECT_GE(acc.alpha, 0.99);                // the ray terminates
    EXPECT_GE(acc.depth, terminationDepth(0.99));
    EXPECT_EQ(samplesToTermination(0, sigma, 0.5, terminationDepth(0.99)), 1.0);
}

TEST(RenderSpanAccumulator, SpansFactorize) {
    // One span of n samples composites exactly like n samples of the same colour and extinction.
    const Vec3d c{0.2, 0.5, 0.9};
    const double sigma = 0.37, dt = 0.25;
    Accumulator steps, span;
    steps.composite({0.1, 0.1, 0.1}, 0.3, -std::log1p(-0.3));
    span.composite({0.1, 0.1, 0.1}, 0.3, -std::log1p(-0.3));
    for (int i = 0; i < 17; ++i) steps.composite(c, spanOpacity(sigma, dt), sigma * dt);
    span.composite(c, spanOpacity(sigma, 17 * dt), sigma * 17 * dt);
    EXPECT_NEAR(steps.alpha, span.alpha, 1e-15);
    EXPECT_NEAR(steps.depth, span.depth, 1e-15);
    EXPECT_NEAR(span.depth, -std::log1p(-span.alpha), 1e-15);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(steps.colour[a], span.colour[a], 1e-15);
}

TEST(RenderSpanTermination, SpanStopsWhereSamplesWould) {
    // alpha 0.5 per sample from A = 0: 1 - 0.5^7 = 0.992 is the first >= 0.99.
    const double dt = 0.5, sigma = extinctionFromOpacity(0.5, dt), ertDepth = terminationDepth(0.99);
    EXPECT_EQ(samplesToTermination(0, sigma, dt, ertDepth), 7.0);
    EXPECT_EQ(samplesToTermination(-std::log1p(-0.995), sigma, dt, ertDepth), 1.0);
    EXPECT_EQ(samplesToTermination(0.2, 0, dt, ertDepth), kInf);
    EXPECT_EQ(samplesToTermination(0.2, sigma, dt, terminationDepth(1.0)), kInf);  // ert = 1: never
    for (double alpha0 : {0.0, 0.3, 0.9})
        for (double a : {1e-6, 0.01, 0.2, 0.7}) {
            const double s = extinctionFromOpacity(a, dt);
            Accumulator acc;
            acc.alpha = alpha0;
            acc.depth = -std::log1p(-alpha0);
            int m = 0;
            while (acc.alpha < 0.99) {
                acc.composite({1, 1, 1}, spanOpacity(s, dt), s * dt);
                ++m;
            }
            EXPECT_EQ(samplesToTermination(-std::log1p(-alpha0), s, dt, ertDepth), double(m)) << alpha0 << " " << a;
        }
    // Exactly on the threshold: alpha 1/2 per sample reaches ert = 1 - 2^-k at sample k, never one later.
    for (int k = 1; k <= 20; ++k)
        EXPECT_EQ(samplesToTermination(0, sigma, dt, terminationDepth(1 - std::ldexp(1.0, -k))), double(k)) << k;
}

TEST(RenderSpanShading, FlatTwoSidedAndFinite) {
    const Vec3d colour{0.5, 0.25, 1}, toEye{0, 0, 1};
    const ShadingModel m;
    // Facing the headlight: ambient + full diffuse + full highlight.
    const Vec3d lit = shade(colour, {0, 0, 1}, toEye, toEye);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(lit[a], colour[a] * (m.ambient + m.diffuse) + m.specular, 1e-15);
    // Two-sided: a back-facing normal shades like the front one.
    const Vec3d back = shade(colour, {0, 0.6, -0.8}, toEye, toEye);
    const Vec3d front = shade(colour, {0, -0.6, 0.8}, toEye, toEye);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(back[a], front[a]);
    // Flat voxel: ambient + diffuse with the view vector as normal, no highlight, never NaN.
    const Vec3d light = normalize(Vec3d{1, 0, 1});
    const Vec3d flat = shade(colour, {0, 0, 0}, toEye, light);
    for (int a = 0; a < 3; ++a) {
        EXPECT_TRUE(std::isfinite(flat[a]));
        EXPECT_NEAR(flat[a], colour[a] * (m.ambient + m.diffuse * std::sqrt(0.5)), 1e-15);
    }
    // Light from behind the surface: diffuse (two-sided) but no highlight.
    const Vec3d behind = shade(colour, {0, 0, 1}, toEye, {0, 0, -1});
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(behind[a], colour[a] * (m.ambient + m.diffuse), 1e-15);
}

}  // namespace
}  // namespace vr
