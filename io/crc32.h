// CRC-32 (zlib's) of large buffers: computed in blocks on all threads and combined. The prepared file's checksums (of
// its header and of each compressed block), and the benchmarks' bit-for-bit checks of a faster stage.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vr {

// Blocks checksummed on their own, on all threads, and combined.
constexpr std::size_t kCrcBlock = std::size_t(8) << 20;

// The CRC of `bytes` bytes at data, continuing from `crc` (the CRC of what comes before them; 0: nothing).
uint32_t crc32Of(const void* data, std::size_t bytes, uint32_t crc = 0);
template <typename T>
uint32_t crc32Of(const std::vector<T>& v, uint32_t crc = 0) {
    return crc32Of(v.data(), v.size() * sizeof(T), crc);
}

// The CRC of two buffers one after the other, from their CRCs and the second one's length.
uint32_t crc32Combine(uint32_t first, uint32_t second, std::size_t secondBytes);

}  // namespace vr
