// Element-wise minima and maxima of byte rows, 16 bytes at a time: the hot loops of the field builders.
// Written with GCC/Clang vector types because -O2's cost model leaves loops of unknown length scalar.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>

namespace vr {

using Bytes16 = uint8_t __attribute__((vector_size(16)));

inline Bytes16 loadBytes(const uint8_t* p) {
    Bytes16 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline Bytes16 minBytes(Bytes16 a, Bytes16 b) { return a < b ? a : b; }
inline Bytes16 maxBytes(Bytes16 a, Bytes16 b) { return a > b ? a : b; }

// out[k] = min(a[k], b[k]) for k < n.
inline void minOfRows(const uint8_t* a, const uint8_t* b, uint8_t* out, int n) {
    int k = 0;
    for (; k + 16 <= n; k += 16) {
        const Bytes16 m = minBytes(loadBytes(a + k), loadBytes(b + k));
        std::memcpy(out + k, &m, sizeof m);
    }
    for (; k < n; ++k) out[k] = std::min(a[k], b[k]);
}

// out[k] = min(a[k], b[k], c[k], d[k]) for k < n.
inline void minOfRows(const uint8_t* a, const uint8_t* b, const uint8_t* c, const uint8_t* d, uint8_t* out, int n) {
    int k = 0;
    for (; k + 16 <= n; k += 16) {
        const Bytes16 m = minBytes(minBytes(loadBytes(a + k), loadBytes(b + k)),
                                   minBytes(loadBytes(c + k), loadBytes(d + k)));
        std::memcpy(out + k, &m, sizeof m);
    }
    for (; k < n; ++k) out[k] = std::min(std::min(a[k], b[k]), std::min(c[k], d[k]));
}

// The largest of p[0 .. n).
inline uint8_t maxOfRow(const uint8_t* p, std::size_t n) {
    Bytes16 m{};
    std::size_t k = 0;
    for (; k + 16 <= n; k += 16) m = maxBytes(m, loadBytes(p + k));
    uint8_t best = 0;
    for (int q = 0; q < 16; ++q) best = std::max(best, m[q]);
    for (; k < n; ++k) best = std::max(best, p[k]);
    return best;
}

}  // namespace vr
