#include "sweep/metrics/image_error.h"

#include <algorithm>
#include <cmath>

#include "sweep/metrics/pixel_fractions.h"
#include "sweep/metrics/rmse.h"
#include "sweep/metrics/ssim.h"

namespace vr {

ImageError imageError(const Image& reference, const Image& image) {
    const Difference d = difference(reference, image);
    return {d.mse, d.psnr(), d.maxAbs, ssim(reference, image), percentOff8Bit(reference, image),
            percentPerceptual(reference, image)};
}

ErrorSummary summarize(const std::vector<ImageError>& views) {
    ErrorSummary s;
    if (views.empty()) return s;
    s.worst = views.front();
    ImageError sum{};
    sum.ssim = 0;
    for (const ImageError& e : views) {
        sum.mse += e.mse;
        sum.maxAbs += e.maxAbs;
        sum.ssim += e.ssim;
        sum.percentOff8Bit += e.percentOff8Bit;
        sum.percentPerceptual += e.percentPerceptual;
        s.worst.mse = std::max(s.worst.mse, e.mse);
        s.worst.psnr = std::min(s.worst.psnr, e.psnr);
        s.worst.maxAbs = std::max(s.worst.maxAbs, e.maxAbs);
        s.worst.ssim = std::min(s.worst.ssim, e.ssim);
        s.worst.percentOff8Bit = std::max(s.worst.percentOff8Bit, e.percentOff8Bit);
        s.worst.percentPerceptual = std::max(s.worst.percentPerceptual, e.percentPerceptual);
    }
    const double n = double(views.size());
    s.mean = {sum.mse / n, psnrOf(sum.mse / n), sum.maxAbs / n, sum.ssim / n, sum.percentOff8Bit / n,
              sum.percentPerceptual / n};
    return s;
}

Image errorMap(const Image& reference, const Image& image, float gain) {
    requireSameSize(reference, image);
    Image map(image.width, image.height);
    for (std::size_t i = 0; i < map.rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c)
            map.rgba[i + c] = std::min(1.f, gain * std::abs(image.rgba[i + c] - reference.rgba[i + c]));
        map.rgba[i + 3] = 1;
    }
    return map;
}

}  // namespace vr
