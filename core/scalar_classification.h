// How a sample is classified (docs/ALGORITHMS.md section 2): the transfer function tabulated over the scalar range,
// and the length below which a gradient is flat. With the scalars it is all a renderer needs: no classified copy
// of the volume is made for rendering, on the host, on the device or in the prepared file.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace vr {

// Opacity alpha per reference step dt0 <-> extinction sigma per world unit.
// alpha = 1 is clamped to a large finite sigma so that spans stay finite.
constexpr double kMaxOpacityPerStep = 1.0 - 1e-12;
inline double extinctionFromOpacity(double alpha, double dt0) {
    return -std::log1p(-std::min(alpha, kMaxOpacityPerStep)) / dt0;
}
inline double opacityFromExtinction(double sigma, double length) { return -std::expm1(-sigma * length); }

// The transfer function at evenly spaced scalars: entry i classifies the scalar lo + i step; a scalar between two
// entries takes extinction and colour interpolated linearly between them, one outside takes the end entry's.
struct TransferTable {
    double lo = 0, step = 1;
    std::vector<float> sigma;                  // extinction per world unit (the TF's opacity per dt0, converted)
    std::vector<std::array<float, 3>> colour;  // linear RGB in [0,1]

    std::size_t size() const { return sigma.size(); }
    // The entries as four floats each, r, g, b, sigma: the prepared file's chunk and the device's buffer.
    std::vector<float> interleaved() const {
        std::vector<float> out;
        out.reserve(4 * size());
        for (std::size_t i = 0; i < size(); ++i)
            out.insert(out.end(), {colour[i][0], colour[i][1], colour[i][2], sigma[i]});
        return out;
    }
    bool operator==(const TransferTable&) const = default;
};

struct ScalarClassification {
    TransferTable table;
    double referenceStep = 1;  // dt0 in world units: the length over which the TF's opacity is given
    double flatGradient = 0;   // a gradient this long or shorter (per world unit) is flat: no normal
    bool operator==(const ScalarClassification&) const = default;
};

}  // namespace vr
