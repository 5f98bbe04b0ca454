// Per-pixel differences of two images over their linear RGB channels (alpha is not compared: the images are
// composited over the background already).
#pragma once
#include "render/image.h"

namespace vr {

struct Difference {
    double mse = 0;     // mean over pixels and the three channels of (a - b)^2
    double maxAbs = 0;  // max over pixels and channels of |a - b|
    double rmse() const;
    double psnr() const;  // dB with peak 1: 10 log10(1 / mse); +inf when the images are equal
};

// Throws InputError when the sizes differ.
Difference difference(const Image& reference, const Image& image);

// PSNR of a mean squared error (peak 1); +inf for 0.
double psnrOf(double mse);

// Throws InputError naming both sizes unless a and b have the same width and height.
void requireSameSize(const Image& a, const Image& b);

}  // namespace vr
