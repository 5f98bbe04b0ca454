#include "volrender/cmd/heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace vr {

Image iterationHeatmap(const std::vector<uint32_t>& iterations, int width, int height) {
    static constexpr std::array<std::array<float, 3>, 5> kRamp{
        {{0.05f, 0.05f, 0.35f}, {0.1f, 0.4f, 0.9f}, {0.2f, 0.85f, 0.85f}, {0.95f, 0.9f, 0.2f}, {0.9f, 0.1f, 0.05f}}};
    const uint32_t most = iterations.empty() ? 0 : *std::max_element(iterations.begin(), iterations.end());
    Image image(width, height);
    for (std::size_t i = 0; i < iterations.size(); ++i) {
        const float x = most ? float(iterations[i]) / float(most) * float(kRamp.size() - 1) : 0.f;
        const std::size_t lo = std::min<std::size_t>(std::size_t(x), kRamp.size() - 2);
        const float w = x - float(lo);
        float* p = &image.rgba[i * 4];
        for (int c = 0; c < 3; ++c) p[c] = kRamp[lo][c] * (1 - w) + kRamp[lo + 1][c] * w;
        p[3] = 1;
    }
    return image;
}

}  // namespace vr
