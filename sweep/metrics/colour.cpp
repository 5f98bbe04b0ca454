#include "sweep/metrics/colour.h"

#include <algorithm>
#include <cmath>

namespace vr {

int srgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return int(std::lround(255 * encoded));
}

double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

Lab linearRgbToLab(double r, double g, double b) {
    r = std::clamp(r, 0.0, 1.0);
    g = std::clamp(g, 0.0, 1.0);
    b = std::clamp(b, 0.0, 1.0);
    // IEC 61966-2-1 matrix; the D65 white is its image of (1,1,1).
    const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    constexpr double xn = 0.4124564 + 0.3575761 + 0.1804375;
    constexpr double yn = 0.2126729 + 0.7151522 + 0.0721750;
    constexpr double zn = 0.0193339 + 0.1191920 + 0.9503041;
    auto f = [](double t) {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
    };
    const double fx = f(x / xn), fy = f(y / yn), fz = f(z / zn);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

}  // namespace vr
