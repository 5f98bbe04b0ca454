// The classified volume (docs/ALGORITHMS.md section 2): per voxel extinction, colour and normal, as nearest samples
// classify; what segmentation keys its regions on.
#pragma once
#include <array>
#include <vector>

#include "grid.h"
#include "scalar_classification.h"

namespace vr {

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
