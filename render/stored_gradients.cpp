#include "render/stored_gradients.h"

#include <algorithm>
#include <cmath>

#include "core/gradient.h"

namespace vr {

int GradientPacker::baseFor(double largest) {
    constexpr int kMax = device::kGradientMantissaMax, kTop = device::kGradientExponentMax;
    if (!(largest > 0) || !std::isfinite(largest)) return 0;
    int base = int(std::ceil(std::log2(largest / kMax))) - kTop;
    while (std::ldexp(double(kMax), base + kTop) < largest) ++base;  // log2's rounding, either way
    while (std::ldexp(double(kMax), base - 1 + kTop) >= largest) --base;
    return base;
}

GradientPacker::GradientPacker(const Volume& scalars, const TransferTable& table)
    : GradientPacker(baseFor(table.step * double(table.size() > 0 ? table.size() - 1 : 0) /
                             scalars.grid.smallestSpacing())) {
    floatValues(scalars);  // packRow reads them
}

GradientPacker::GradientPacker(int base) : base_(base) {
    for (int e = 0; e < kExponents; ++e) {
        longest_[e] = std::ldexp(device::kGradientMantissaMax + 0.5, e + base);
        inverseUnit_[e] = std::ldexp(1.0, -(e + base));
    }
}

std::uint32_t GradientPacker::pack(const Vec3d& g) const {
    const double longest = std::max({std::abs(g.x), std::abs(g.y), std::abs(g.z)});
    if (!(longest > 0) || !std::isfinite(g.x + g.y + g.z)) return 0;  // no direction to store
    const int e = int(std::lower_bound(longest_.begin(), longest_.end() - 1, longest) - longest_.begin());
    const double inverse = inverseUnit_[e];
    constexpr double kMax = device::kGradientMantissaMax;
    const auto mantissa = [&](double c) {
        return std::uint32_t(int(std::nearbyint(std::clamp(c * inverse, -kMax, kMax)))) & 511u;
    };
    return std::uint32_t(e) << 27u | mantissa(g.x) << 18u | mantissa(g.y) << 9u | mantissa(g.z);
}

void GradientPacker::packRow(const Volume& scalars, std::size_t first, int count, std::uint32_t* to) const {
    const Vec3i& n = scalars.grid.dims;
    const std::size_t slice = std::size_t(n.x) * n.y;
    const int z = int(first / slice), y = int(first % slice / n.x), x0 = int(first % n.x);
    constexpr int kRun = 256;  // the gradients of a run of the row at a time
    double gx[kRun], gy[kRun], gz[kRun];
    for (int done = 0; done < count; done += kRun) {
        const int run = std::min(kRun, count - done);
        centralGradientRun(scalars, x0 + done, run, y, z, gx, gy, gz);
        for (int i = 0; i < run; ++i) to[done + i] = pack({gx[i], gy[i], gz[i]});
    }
}

Vec3d GradientPacker::stored(const Volume& scalars, const Vec3i& v) const {
    return device::unpackGradient(pack(centralGradient(scalars, v.x, v.y, v.z)), base_);
}

}  // namespace vr
