#include "sweep/metrics/rmse.h"

#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"

namespace vr {

void requireSameSize(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw InputError("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                         " image with a " + std::to_string(b.width) + "x" + std::to_string(b.height) + " one");
}

double psnrOf(double mse) {
    return mse > 0 ? -10 * std::log10(mse) : std::numeric_limits<double>::infinity();
}

double Difference::rmse() const { return std::sqrt(mse); }
double Difference::psnr() const { return psnrOf(mse); }

Difference difference(const Image& reference, const Image& image) {
    requireSameSize(reference, image);
    Difference d;
    const std::size_t pixels = std::size_t(image.width) * image.height;
    double sum = 0;
    for (std::size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) {
            const double e = double(image.rgba[p * 4 + c]) - double(reference.rgba[p * 4 + c]);
            sum += e * e;
            d.maxAbs = std::max(d.maxAbs, std::abs(e));
        }
    d.mse = pixels ? sum / double(pixels * 3) : 0;
    return d;
}

}  // namespace vr
