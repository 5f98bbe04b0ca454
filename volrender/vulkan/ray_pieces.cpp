#include "volrender/vulkan/ray_pieces.h"

#include <algorithm>
#include <bit>

#include "shaders/ray_math.h"

namespace vr {

int raysPieces(bool discreteGpu, std::size_t listPixels, std::size_t framePixels) {
    if (!discreteGpu || listPixels == 0) return 1;
    return int(std::clamp<std::size_t>(framePixels / listPixels, 1, kMostPieces));
}

RayFromPieces compositePieces(const device::uvec4* colours, const device::uvec4* counts, std::size_t first,
                              std::size_t stride, int pieces, const Vec3d& background) {
    constexpr uint32_t failures = device::kFailed | device::kCutShort;
    double rgb[3] = {0, 0, 0}, depth = 0;  // what the pieces so far gathered, and their optical depth
    uint32_t flags = 0;
    RayFromPieces ray;
    for (int j = 0; j < pieces; ++j) {
        const std::size_t at = first + std::size_t(j) * stride;
        const device::uvec4& c = colours[at];
        flags |= device::failureFlagsOf(c.w);
        const double transmittance = 1 - device::spanOpacity(depth);
        rgb[0] += transmittance * std::bit_cast<float>(c.x);
        rgb[1] += transmittance * std::bit_cast<float>(c.y);
        rgb[2] += transmittance * std::bit_cast<float>(c.z);
        if (!(flags & failures)) depth += std::bit_cast<float>(c.w);
        if (!counts) continue;
        ray.samples += counts[at].x;
        ray.iterations += counts[at].y & ~failures;
        flags |= counts[at].y & failures;
    }
    // As the caster's last lines make a whole ray's pixel.
    const double alpha = device::spanOpacity(depth);
    ray.colour = {std::bit_cast<uint32_t>(float(rgb[0] + background.x * (1 - alpha))),
                  std::bit_cast<uint32_t>(float(rgb[1] + background.y * (1 - alpha))),
                  std::bit_cast<uint32_t>(float(rgb[2] + background.z * (1 - alpha))),
                  flags & failures ? device::failureAlphaBits(flags) : std::bit_cast<uint32_t>(float(alpha))};
    ray.iterations |= flags & failures;
    return ray;
}

}  // namespace vr
