// Every error figure of one image against its reference (docs/BENCH.md "Error"), and their summary over the views.
#pragma once
#include <vector>

#include "render/image.h"

namespace vr {

struct ImageError {
    double mse = 0, psnr = 0, maxAbs = 0, ssim = 1;
    double percentOff8Bit = 0;     // 8-bit value off by more than 1
    double percentPerceptual = 0;  // CIEDE2000 > 2.3
};

ImageError imageError(const Image& reference, const Image& image);

// Over the views: `mean` averages each figure except PSNR, which is that of the mean MSE (so an exact view does
// not make it infinite); `worst` is each figure's worst view (largest error, smallest PSNR and SSIM).
struct ErrorSummary {
    ImageError mean, worst;
};
ErrorSummary summarize(const std::vector<ImageError>& views);

// |image - reference| times `gain` per linear RGB channel, opaque: an error map to look at.
Image errorMap(const Image& reference, const Image& image, float gain = 10);

}  // namespace vr
