// What every renderer (CPU reference or Vulkan) returns: the image and the per-pixel work counters.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/image.h"

namespace vr {

struct RenderResult {
    Image image;
    // Per pixel, where the render counted them (RenderSettings::rayCounts), else empty: the loop iterations
    // (fetches) of its ray, and the lattice samples those iterations stood for.
    std::vector<uint32_t> iterations;
    std::vector<uint64_t> samples;
    double deviceMilliseconds = 0;     // Vulkan: timestamp queries around the dispatches; CPU: 0
    double wallMilliseconds = 0;

    // A width x height image with every pixel's counters at zero (none without `counts`), for a renderer to fill.
    static RenderResult blank(int width, int height, bool counts = true) {
        RenderResult r;
        r.image = Image(width, height);
        const std::size_t pixels = std::size_t(width) * std::size_t(height);
        if (counts) {
            r.iterations.assign(pixels, 0);
            r.samples.assign(pixels, 0);
        }
        return r;
    }
};

}  // namespace vr
