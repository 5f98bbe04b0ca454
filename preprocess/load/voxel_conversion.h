// Widening stored voxels (uint8/int16/uint16/float32, either byte order) to the float values a Volume holds.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/volume.h"

namespace vr {

// Converts `count` voxels of type T stored at `bytes` into `out`; swaps bytes when the file's order is not the
// machine's. Bytes are copied per voxel, so `bytes` needs no alignment (gzip/file buffers are plain bytes).
template <typename T>
void widenVoxels(const unsigned char* bytes, std::size_t count, bool swapBytes, float* out) {
    using Bits = std::conditional_t<sizeof(T) == 1, std::uint8_t,
                                    std::conditional_t<sizeof(T) == 2, std::uint16_t, std::uint32_t>>;
    for (std::size_t i = 0; i < count; ++i) {
        Bits b;
        std::memcpy(&b, bytes + i * sizeof(T), sizeof(T));
        if constexpr (sizeof(T) == 2)
            if (swapBytes) b = __builtin_bswap16(b);
        if constexpr (sizeof(T) == 4)
            if (swapBytes) b = __builtin_bswap32(b);
        out[i] = static_cast<float>(std::bit_cast<T>(b));
    }
}

// The same for a ScalarType known only at run time.
inline void widenVoxels(ScalarType type, const unsigned char* bytes, std::size_t count, bool swapBytes, float* out) {
    switch (type) {
        case ScalarType::UInt8: widenVoxels<std::uint8_t>(bytes, count, swapBytes, out); break;
        case ScalarType::Int16: widenVoxels<std::int16_t>(bytes, count, swapBytes, out); break;
        case ScalarType::UInt16: widenVoxels<std::uint16_t>(bytes, count, swapBytes, out); break;
        case ScalarType::Float32: widenVoxels<float>(bytes, count, swapBytes, out); break;
    }
}

}  // namespace vr
