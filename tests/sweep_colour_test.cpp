// CIEDE2000 against the published test data of Sharma, Wu and Dalal (2005), Table 1, and the colour conversions
// it is fed with.
#include <gtest/gtest.h>

#include "sweep/metrics/ciede2000.h"
#include "sweep/metrics/colour.h"

namespace vr {
namespace {

struct Pair {
    int number;
    Lab lab1, lab2;
    double deltaE;
};

// Pairs chosen to cover the paper's traps: the hue-angle wrap (9-15), a' with zero chroma (7, 8), and real colours.
const Pair kPairs[] = {
    {1, {50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {2, {50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {4, {50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {7, {50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {8, {50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {9, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {10, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {11, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {12, {50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {13, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {14, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {15, {50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {16, {50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {17, {50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {19, {50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {25, {60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {27, {61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {31, {90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {33, {6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {34, {2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};

TEST(SweepColourCiede2000, MatchesSharmaTestData) {
    for (const Pair& p : kPairs) {
        EXPECT_NEAR(ciede2000(p.lab1, p.lab2), p.deltaE, 1e-4) << "pair " << p.number;
        EXPECT_NEAR(ciede2000(p.lab2, p.lab1), p.deltaE, 1e-4) << "pair " << p.number << " swapped";
    }
}

TEST(SweepColourCiede2000, ZeroForEqualColours) {
    EXPECT_EQ(ciede2000({50, 10, -20}, {50, 10, -20}), 0.0);
    EXPECT_EQ(ciede2000({0, 0, 0}, {0, 0, 0}), 0.0);
}

TEST(SweepColourConversions, LabOfWhiteBlackAndPrimaries) {
    const Lab white = linearRgbToLab(1, 1, 1);
    EXPECT_NEAR(white[0], 100, 1e-6);
    EXPECT_NEAR(white[1], 0, 1e-6);
    EXPECT_NEAR(white[2], 0, 1e-6);
    const Lab black = linearRgbToLab(0, 0, 0);
    EXPECT_NEAR(black[0], 0, 1e-9);
    // sRGB red (255, 0, 0) is L* 53.24, a* 80.09, b* 67.20 (D65).
    const Lab red = linearRgbToLab(1, 0, 0);
    EXPECT_NEAR(red[0], 53.24, 0.01);
    EXPECT_NEAR(red[1], 80.09, 0.01);
    EXPECT_NEAR(red[2], 67.20, 0.01);
    // Values outside [0,1] clamp.
    EXPECT_EQ(linearRgbToLab(2, -1, 1.5), linearRgbToLab(1, 0, 1));
}

TEST(SweepColourConversions, EightBitSrgbAndLuminance) {
    EXPECT_EQ(srgb8(0), 0);
    EXPECT_EQ(srgb8(1), 255);
    EXPECT_EQ(srgb8(0.5), 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
    EXPECT_EQ(srgb8(-3), 0);
    EXPECT_EQ(srgb8(7), 255);
    EXPECT_NEAR(luminance(1, 1, 1), 1, 1e-12);
    EXPECT_NEAR(luminance(0, 1, 0), 0.7152, 1e-12);
}

}  // namespace
}  // namespace vr
