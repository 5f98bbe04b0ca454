#include "sweep/metrics/ciede2000.h"

#include <cmath>
#include <numbers>

namespace vr {

namespace {
constexpr double kPi = std::numbers::pi;
double deg(double radians) { return radians * 180 / kPi; }
double rad(double degrees) { return degrees * kPi / 180; }

// Hue angle in [0, 360) degrees; 0 where a' = b = 0 (the paper's convention, eq. 7).
double hueAngle(double b, double ap) {
    if (b == 0 && ap == 0) return 0;
    const double h = deg(std::atan2(b, ap));
    return h < 0 ? h + 360 : h;
}
}  // namespace

double ciede2000(const Lab& lab1, const Lab& lab2) {
    const auto [L1, a1, b1] = lab1;
    const auto [L2, a2, b2] = lab2;
    // Step 1: C', h' (eqs. 2-7).
    const double cBar = (std::hypot(a1, b1) + std::hypot(a2, b2)) / 2;
    const double c7 = std::pow(cBar, 7);
    const double g = 0.5 * (1 - std::sqrt(c7 / (c7 + std::pow(25.0, 7))));
    const double a1p = (1 + g) * a1, a2p = (1 + g) * a2;
    const double c1p = std::hypot(a1p, b1), c2p = std::hypot(a2p, b2);
    const double h1p = hueAngle(b1, a1p), h2p = hueAngle(b2, a2p);

    // Step 2: dL', dC', dH' (eqs. 8-11).
    const double dLp = L2 - L1;
    const double dCp = c2p - c1p;
    double dhp = 0;
    if (c1p * c2p != 0) {
        dhp = h2p - h1p;
        if (dhp > 180) dhp -= 360;
        else if (dhp < -180) dhp += 360;
    }
    const double dHp = 2 * std::sqrt(c1p * c2p) * std::sin(rad(dhp / 2));

    // Step 3: the weighting functions and the rotation term (eqs. 12-22).
    const double lBarP = (L1 + L2) / 2;
    const double cBarP = (c1p + c2p) / 2;
    double hBarP = h1p + h2p;
    if (c1p * c2p != 0) {
        if (std::abs(h1p - h2p) <= 180) hBarP = (h1p + h2p) / 2;
        else if (h1p + h2p < 360) hBarP = (h1p + h2p + 360) / 2;
        else hBarP = (h1p + h2p - 360) / 2;
    }
    const double t = 1 - 0.17 * std::cos(rad(hBarP - 30)) + 0.24 * std::cos(rad(2 * hBarP)) +
                     0.32 * std::cos(rad(3 * hBarP + 6)) - 0.20 * std::cos(rad(4 * hBarP - 63));
    const double dTheta = 30 * std::exp(-std::pow((hBarP - 275) / 25, 2));
    const double cBarP7 = std::pow(cBarP, 7);
    const double rC = 2 * std::sqrt(cBarP7 / (cBarP7 + std::pow(25.0, 7)));
    const double l50 = (lBarP - 50) * (lBarP - 50);
    const double sL = 1 + 0.015 * l50 / std::sqrt(20 + l50);
    const double sC = 1 + 0.045 * cBarP;
    const double sH = 1 + 0.015 * cBarP * t;
    const double rT = -std::sin(rad(2 * dTheta)) * rC;

    const double l = dLp / sL, c = dCp / sC, h = dHp / sH;
    return std::sqrt(l * l + c * c + h * h + rT * c * h);
}

}  // namespace vr
