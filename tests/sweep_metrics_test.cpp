// The image error metrics on images whose answers are known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/errors.h"
#include "sweep/metrics/image_error.h"
#include "sweep/metrics/pixel_fractions.h"
#include "sweep/metrics/rmse.h"
#include "sweep/metrics/ssim.h"

namespace vr {
namespace {

// A reproducible image with structure (gradient plus noise), values in [0.1, 0.8].
Image testImage(int w, int h, uint32_t seed = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(0.f, 0.2f);
    Image im(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = im.pixel(x, y);
            for (int c = 0; c < 3; ++c) p[c] = 0.1f + 0.5f * float(x + c * y) / float(w + 2 * h) + noise(rng);
            p[3] = 1;
        }
    return im;
}

Image offset(Image im, float d) {
    for (std::size_t i = 0; i < im.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) im.rgba[i + c] += d;
    return im;
}

TEST(SweepMetrics, IdenticalImages) {
    const Image a = testImage(40, 30);
    const ImageError e = imageError(a, a);
    EXPECT_EQ(e.mse, 0);
    EXPECT_TRUE(std::isinf(e.psnr) && e.psnr > 0);
    EXPECT_EQ(e.maxAbs, 0);
    EXPECT_NEAR(e.ssim, 1, 1e-12);
    EXPECT_EQ(e.percentOff8Bit, 0);
    EXPECT_EQ(e.percentPerceptual, 0);
}

TEST(SweepMetrics, ConstantOffsetGivesKnownRmseAndPsnr) {
    const Image a = testImage(32, 32);
    const float d = 0.01f;
    const Difference diff = difference(a, offset(a, d));
    EXPECT_NEAR(diff.rmse(), d, 1e-6);
    EXPECT_NEAR(diff.psnr(), 40.0, 1e-3);  // -20 log10(0.01)
    EXPECT_NEAR(diff.maxAbs, d, 1e-6);
    EXPECT_NEAR(difference(a, offset(a, 0.1f)).psnr(), 20.0, 1e-3);
}

TEST(SweepMetrics, AlphaIsNotCompared) {
    Image a = testImage(16, 16), b = a;
    for (std::size_t i = 3; i < b.rgba.size(); i += 4) b.rgba[i] = 0.25f;
    EXPECT_EQ(difference(a, b).mse, 0);
}

TEST(SweepMetrics, SsimFallsWithNoiseAndIsOneForABrightnessFreeCopy) {
    const Image a = testImage(64, 64, 3);
    Image noisy = a;
    std::mt19937 rng(7);
    std::normal_distribution<float> n(0.f, 0.1f);
    for (std::size_t i = 0; i < noisy.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) noisy.rgba[i + c] += n(rng);
    const double s = ssim(a, noisy);
    EXPECT_LT(s, 0.9);
    EXPECT_GT(s, 0.0);
    // A small constant offset keeps the structure: SSIM stays near 1 but below it.
    const double shifted = ssim(a, offset(a, 0.01f));
    EXPECT_LT(shifted, 1.0);
    EXPECT_GT(shifted, 0.99);
    // Symmetric.
    EXPECT_NEAR(ssim(noisy, a), s, 1e-12);
}

TEST(SweepMetrics, SsimOfUniformImagesFollowsTheLuminanceTerm) {
    // Two flat images of luminance m1, m2: SSIM = (2 m1 m2 + C1) / (m1^2 + m2^2 + C1) (no variance).
    Image a(20, 20), b(20, 20);
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            a.rgba[i + c] = 0.2f;
            b.rgba[i + c] = 0.4f;
        }
    const double c1 = 1e-4, m1 = 0.2, m2 = 0.4;
    EXPECT_NEAR(ssim(a, b), (2 * m1 * m2 + c1) / (m1 * m1 + m2 * m2 + c1), 1e-6);
}

TEST(SweepMetrics, PercentOff8BitCountsPixelsBeyondOneLevel) {
    Image a(10, 10), b(10, 10);  // black
    // 7 pixels of 100 brighter by 3/255 in sRGB terms (linear values that encode to 3 and 1).
    for (int i = 0; i < 7; ++i) b.pixel(i, 0)[1] = 3.f / 255 / 12.92f;
    for (int i = 0; i < 5; ++i) b.pixel(i, 1)[2] = 1.f / 255 / 12.92f;  // off by exactly 1: not counted
    EXPECT_NEAR(percentOff8Bit(a, b), 7.0, 1e-12);
    EXPECT_NEAR(percentOff8Bit(a, b, 0), 12.0, 1e-12);
}

TEST(SweepMetrics, PercentPerceptualCountsVisibleColourChanges) {
    Image a(10, 10), b(10, 10);
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) a.rgba[i + c] = b.rgba[i + c] = 0.5f;
    for (int x = 0; x < 10; ++x) b.pixel(x, 0)[0] = 0.6f;     // a clearly visible red shift: 10 %
    b.pixel(0, 5)[1] = 0.5001f;                                // invisible
    EXPECT_NEAR(percentPerceptual(a, b), 10.0, 1e-12);
    EXPECT_EQ(percentPerceptual(a, a), 0);
}

TEST(SweepMetrics, SummaryTakesMeansAndWorstViews) {
    ImageError exact{0, INFINITY, 0, 1, 0, 0};
    ImageError off{1e-4, 40, 0.02, 0.9, 2, 1};
    const ErrorSummary s = summarize({exact, off});
    EXPECT_NEAR(s.mean.mse, 5e-5, 1e-12);
    EXPECT_NEAR(s.mean.psnr, 10 * std::log10(2e4), 1e-9);  // PSNR of the mean MSE: finite
    EXPECT_EQ(s.worst.psnr, 40);
    EXPECT_EQ(s.worst.ssim, 0.9);
    EXPECT_NEAR(s.mean.ssim, 0.95, 1e-12);
    EXPECT_EQ(s.worst.percentOff8Bit, 2);
    EXPECT_EQ(s.mean.percentPerceptual, 0.5);
}

TEST(SweepMetrics, ErrorMapIsScaledAbsoluteDifference) {
    const Image a = testImage(8, 8);
    const Image map = errorMap(a, offset(a, -0.01f), 10);
    for (std::size_t i = 0; i < map.rgba.size(); i += 4) {
        EXPECT_NEAR(map.rgba[i], 0.1f, 1e-5);
        EXPECT_EQ(map.rgba[i + 3], 1.f);
    }
}

TEST(SweepMetrics, BadSizesAreInputErrors) {
    EXPECT_THROW(difference(Image(4, 4), Image(4, 5)), InputError);
    EXPECT_THROW(ssim(Image(10, 10), Image(10, 10)), InputError);  // smaller than the 11x11 window
    EXPECT_THROW(percentPerceptual(Image(4, 4), Image(5, 4)), InputError);
}

}  // namespace
}  // namespace vr
