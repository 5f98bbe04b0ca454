// Iterations per pixel as a colour-mapped image (the thesis' Fig. 4.4): where the caster works hard.
#pragma once
#include <cstdint>
#include <vector>

#include "render/image.h"

namespace vr {

// Maps 0 .. max(iterations) through a blue-cyan-yellow-red ramp; opaque.
Image iterationHeatmap(const std::vector<uint32_t>& iterations, int width, int height);

}  // namespace vr
