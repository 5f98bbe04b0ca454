// Percentages of pixels that differ visibly: in their 8-bit sRGB values, or perceptually (CIEDE2000).
#pragma once
#include "render/image.h"

namespace vr {

constexpr int kEightBitTolerance = 1;       // "off by more than 1/255"
constexpr double kPerceptualDeltaE = 2.3;   // CIEDE2000 just-noticeable difference

// Percent of pixels where some channel's 8-bit sRGB value (as a PNG stores it) differs by more than `tolerance`.
double percentOff8Bit(const Image& reference, const Image& image, int tolerance = kEightBitTolerance);

// Percent of pixels whose CIEDE2000 difference (linear RGB -> Lab D65) exceeds `threshold`.
double percentPerceptual(const Image& reference, const Image& image, double threshold = kPerceptualDeltaE);

}  // namespace vr
