// Stored gradients: the 32-bit code's precision, its range and signs, and the CPU reference shading by it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "datasets/phantoms.h"
#include "preprocess/classify/transfer_function.h"
#include "render/cpu_renderer.h"
#include "render/stored_gradients.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/views.h"
#include "support/volumes.h"

namespace vr {
namespace {

// The unit of code c's exponent for base `base`.
double unitOf(std::uint32_t code, int base) { return std::ldexp(1.0, int(code >> 27) + base); }

TEST(RenderStoredGradients, BaseHoldsTheLargestGradientAtTheTopExponent) {
    for (double largest : {1e-6, 0.37, 1.0, 255.0, 256.0, 4010.0 / 0.25, 3.3e7}) {
        const int base = GradientPacker::baseFor(largest);
        SCOPED_TRACE(largest);
        EXPECT_GE(std::ldexp(255.0, base + 31), largest);
        EXPECT_LT(std::ldexp(255.0, base + 30), largest);
    }
    EXPECT_EQ(GradientPacker::baseFor(0), 0);
    EXPECT_EQ(GradientPacker::baseFor(std::nan("")), 0);
}

TEST(RenderStoredGradients, EachComponentWithinHalfAUnitOfAFinePrecision) {
    const GradientPacker packer(GradientPacker::baseFor(2e4));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> mantissa(-1, 1), exponent(-12, 14);
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::exp2(exponent(rng));
        const Vec3d g{mantissa(rng) * scale, mantissa(rng) * scale * (i % 3 == 0 ? 1e-3 : 1), mantissa(rng) * scale};
        const std::uint32_t code = packer.pack(g);
        const Vec3d back = device::unpackGradient(code, packer.base());
        const double unit = unitOf(code, packer.base());
        const double longest = std::max({std::abs(g.x), std::abs(g.y), std::abs(g.z)});
        for (int a = 0; a < 3; ++a) ASSERT_LE(std::abs(back[a] - g[a]), unit / 2) << i;
        // The least exponent that holds the longest component: its unit is at most 1/127.75 of it, so the
        // direction is off by at most about 2 / 255 radians.
        if ((code >> 27) > 0) {
            ASSERT_LE(unit, longest / 127.75) << i;
        }
        ASSERT_LE(length(back - g), 2.0 / 255 * length(g) + 1e-300) << i;
    }
}

TEST(RenderStoredGradients, ZeroIsCodeZeroAndSignsSurvive) {
    const GradientPacker packer(GradientPacker::baseFor(1000));
    EXPECT_EQ(packer.pack({0, 0, 0}), 0u);
    EXPECT_EQ(device::unpackGradient(0u, packer.base()), (Vec3d{0, 0, 0}));
    const Vec3d back = device::unpackGradient(packer.pack({-3, 250, -1.5}), packer.base());
    EXPECT_LT(back.x, 0);
    EXPECT_GT(back.y, 0);
    EXPECT_LT(back.z, 0);
    // Finer than half the last exponent's unit: flat.
    EXPECT_EQ(device::unpackGradient(packer.pack({1e-12, 0, 0}), packer.base()), (Vec3d{0, 0, 0}));
    // Longer than the volume can hold (a corrupt bound): clamped to the top of the range, signs kept.
    const Vec3d clamped = device::unpackGradient(packer.pack({-1e9, 1e9, 0}), packer.base());
    EXPECT_EQ(clamped.x, -clamped.y);
    EXPECT_LT(clamped.x, 0);
}

TEST(RenderStoredGradients, CpuReferenceShadesAlikeWithEitherSource) {
    const Volume volume = test::centralBlock(test::loadDataset("cranium_ct"), 48);
    const PreparedVolume p = test::prepareVolume(volume, test::datasetTransferFunction("cranium_ct.tf.json"),
                                                 {0, 0, true, true});
    const Camera camera = Camera::fit(p.grid(), test::orbitView(30, 20, 64, 48, Projection::Orthographic));
    for (bool trilinear : {false, true}) {
        RenderSettings s = test::renderSettings(Caster::Primitive, true, trilinear);
        const RenderResult onTheFly = renderCpu(p, camera, s);
        s.gradients = Gradients::Stored;
        const RenderResult stored = renderCpu(p, camera, s);
        SCOPED_TRACE(trilinear ? "trilinear" : "nearest");
        EXPECT_LT(maxAbsDifference(stored.image, onTheFly.image), 2.0 / 255);
        EXPECT_EQ(stored.iterations, onTheFly.iterations);
    }
}

}  // namespace
}  // namespace vr
