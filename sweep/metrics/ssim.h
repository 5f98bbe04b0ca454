// SSIM (Wang, Bovik, Sheikh, Simoncelli 2004) on the linear luminance of two images, with the paper's
// Gaussian window: 11 x 11, sigma 1.5, K1 = 0.01, K2 = 0.03, dynamic range 1. The mean over every pixel where
// the whole window lies inside the image ("valid" positions).
#pragma once
#include "render/image.h"

namespace vr {

constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;

// 1 for identical images; throws InputError when the sizes differ or an image is smaller than the window.
double ssim(const Image& reference, const Image& image);

}  // namespace vr
