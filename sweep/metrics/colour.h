// Colour conversions the error metrics share: linear RGB (sRGB primaries, D65) -> 8-bit sRGB, luminance, CIELAB.
#pragma once
#include <array>

namespace vr {

using Lab = std::array<double, 3>;  // L*, a*, b*

// The 8-bit value a PNG of this linear channel holds (clamped, sRGB curve, rounded): as writeImage stores it.
int srgb8(double linear);

// Relative luminance Y of linear RGB (Rec. 709 / sRGB primaries).
double luminance(double r, double g, double b);

// Linear RGB with sRGB primaries (clamped to [0,1]) -> XYZ -> CIELAB with the D65 white point.
Lab linearRgbToLab(double r, double g, double b);

}  // namespace vr
