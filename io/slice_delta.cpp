#include "io/slice_delta.h"

#include <algorithm>
#include <cstring>

namespace vr {
namespace {

// 16 bytes added or subtracted lane by lane (mod 256): written out, because -O2 leaves a byte loop of unknown
// length unvectorised, and byte by byte the decoding took as long as decompressing.
using Bytes16 = unsigned char __attribute__((vector_size(16)));

template <typename Op>
void eachByte(unsigned char* to, const unsigned char* a, const unsigned char* b, uint64_t n, Op op) {
    uint64_t k = 0;
    for (; k + 16 <= n; k += 16) {
        Bytes16 x, y;
        std::memcpy(&x, a + k, 16);
        std::memcpy(&y, b + k, 16);
        const Bytes16 r = op(x, y);
        std::memcpy(to + k, &r, 16);
    }
    for (; k < n; ++k) to[k] = static_cast<unsigned char>(op(a[k], b[k]));
}

}  // namespace

void sliceDeltaEncode(const unsigned char* block, uint64_t bytes, uint64_t sliceBytes, unsigned char* differences) {
    const uint64_t first = std::min(bytes, sliceBytes);
    std::copy(block, block + first, differences);
    eachByte(differences + first, block + first, block, bytes - first, [](auto x, auto y) { return x - y; });
}

void sliceDeltaDecode(unsigned char* block, uint64_t bytes, uint64_t sliceBytes) {
    // Slice by slice: each slice's bytes need the slice before them decoded.
    for (uint64_t slice = sliceBytes; slice < bytes; slice += sliceBytes)
        eachByte(block + slice, block + slice, block + slice - sliceBytes, std::min(sliceBytes, bytes - slice),
                 [](auto x, auto y) { return x + y; });
}

}  // namespace vr
