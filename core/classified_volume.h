// The classified volume (docs/ALGORITHMS.md section 2): per voxel extinction, colour and normal.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "grid.h"

namespace vr {

// Opacity alpha per reference step dt0 <-> extinction sigma per world unit.
// alpha = 1 is clamped to a large finite sigma so that spans stay finite.
constexpr double kMaxOpacityPerStep = 1.0 - 1e-12;
inline double extinctionFromOpacity(double alpha, double dt0) {
    return -std::log1p(-std::min(alpha, kMaxOpacityPerStep)) / dt0;
}
inline double opacityFromExtinction(double sigma, double length) { return -std::expm1(-sigma * length); }

struct ClassifiedVolume {
    GridGeometry grid;
    double referenceStep = 1.0;  // dt0 in world units: the length over which the TF's opacity is given

    std::vector<float> sigma;                  // extinction per world unit, >= 0
    std::vector<std::array<float, 3>> colour;  // linear RGB in [0,1]
    // Unit normal (from the gradient) or (0,0,0) where the gradient is below the flat floor.
    // Empty when the classification produced no gradients.
    std::vector<std::array<float, 3>> normal;

    bool hasNormals() const { return !normal.empty(); }
    double opacity(std::size_t i) const { return opacityFromExtinction(sigma[i], referenceStep); }
};

}  // namespace vr
