// What every renderer (CPU reference or Vulkan) returns: the image and the per-pixel work counters.
#pragma once
#include <cstddef>
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

    // A width x height image with every pixel's counters at zero, for a renderer to fill.
    static RenderResult blank(int width, int height) {
        RenderResult r;
        r.image = Image(width, height);
        const std::size_t pixels = std::size_t(width) * std::size_t(height);
        r.iterations.assign(pixels, 0);
        r.samples.assign(pixels, 0);
        return r;
    }
};

}  // namespace vr
