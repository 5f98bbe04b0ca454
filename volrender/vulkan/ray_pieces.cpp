#include "volrender/vulkan/ray_pieces.h"

#include <algorithm>

#include "shaders/device_contract.h"

namespace vr {

int raysPieces(bool discreteGpu, std::size_t listPixels, std::size_t framePixels) {
    if (!discreteGpu || listPixels == 0) return 1;
    return int(std::clamp<std::size_t>(framePixels / listPixels, 1, device::kMostPieces));
}

}  // namespace vr
