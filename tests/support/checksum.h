// CRC-32 (zlib) of arrays, continuing from an earlier CRC: the benchmarks print it beside their times, so that a
// faster stage can be checked bit for bit against the last one on volumes too large for the brute-force tests.
#pragma once
#include <zlib.h>

#include <cstdint>
#include <vector>

namespace vr::test {

inline uint32_t crc32Of(const void* data, std::size_t bytes, uint32_t crc = 0) {
    return uint32_t(crc32_z(crc, static_cast<const Bytef*>(data), bytes));
}

template <typename T>
uint32_t crc32Of(const std::vector<T>& v, uint32_t crc = 0) {
    return crc32Of(v.data(), v.size() * sizeof(T), crc);
}

}  // namespace vr::test
