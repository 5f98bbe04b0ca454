// What every renderer (CPU reference or Vulkan) returns: the image and the per-pixel work counters.
#pragma once
#include <cstdint>
#include <vector>

#include "render/image.h"

namespace vr {

struct RenderResult {
    Image image;
    std::vector<uint32_t> iterations;  // per pixel: loop iterations (fetches) of its ray
    std::vector<uint64_t> samples;     // per pixel: lattice samples those iterations stood for
    double deviceMilliseconds = 0;     // Vulkan: timestamp queries around the dispatches; CPU: 0
    double wallMilliseconds = 0;
};

}  // namespace vr
