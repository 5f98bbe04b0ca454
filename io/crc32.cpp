#include "io/crc32.h"

#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>

namespace vr {

uint32_t crc32Combine(uint32_t first, uint32_t second, std::size_t secondBytes) {
    return uint32_t(crc32_combine(first, second, z_off_t(secondBytes)));
}

uint32_t crc32Of(const void* data, std::size_t bytes, uint32_t crc) {
    const auto* p = static_cast<const Bytef*>(data);
    const std::size_t blocks = (bytes + kCrcBlock - 1) / kCrcBlock;
    auto blockBytes = [&](std::size_t b) { return std::min(kCrcBlock, bytes - b * kCrcBlock); };
    if (blocks <= 1) return uint32_t(crc32_z(crc, p, bytes));
    std::vector<uint32_t> crcs(blocks);
    tbb::parallel_for(std::size_t(0), blocks,
                      [&](std::size_t b) { crcs[b] = uint32_t(crc32_z(0, p + b * kCrcBlock, blockBytes(b))); });
    for (std::size_t b = 0; b < blocks; ++b) crc = crc32Combine(crc, crcs[b], blockBytes(b));
    return crc;
}

}  // namespace vr
