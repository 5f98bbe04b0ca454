#include "sweep/metrics/pixel_fractions.h"

#include <cstdlib>

#include "sweep/metrics/ciede2000.h"
#include "sweep/metrics/colour.h"
#include "sweep/metrics/rmse.h"

namespace vr {

namespace {
// Percent of the pixels p for which differs(p) holds.
template <typename Differs>
double percentWhere(const Image& image, Differs differs) {
    const std::size_t pixels = std::size_t(image.width) * image.height;
    std::size_t count = 0;
    for (std::size_t p = 0; p < pixels; ++p) count += differs(p * 4) ? 1 : 0;
    return pixels ? 100.0 * double(count) / double(pixels) : 0;
}
}  // namespace

double percentOff8Bit(const Image& reference, const Image& image, int tolerance) {
    requireSameSize(reference, image);
    return percentWhere(image, [&](std::size_t i) {
        for (int c = 0; c < 3; ++c)
            if (std::abs(srgb8(image.rgba[i + c]) - srgb8(reference.rgba[i + c])) > tolerance) return true;
        return false;
    });
}

double percentPerceptual(const Image& reference, const Image& image, double threshold) {
    requireSameSize(reference, image);
    return percentWhere(image, [&](std::size_t i) {
        const float* a = &reference.rgba[i];
        const float* b = &image.rgba[i];
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) return false;
        return ciede2000(linearRgbToLab(a[0], a[1], a[2]), linearRgbToLab(b[0], b[1], b[2])) > threshold;
    });
}

}  // namespace vr
