// Element-wise minima and maxima of byte rows, 16 bytes at a time: the hot loops of the field builders.
// Written with GCC/Clang vector types because -O2's cost model leaves loops of unknown length scalar.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace vr {

using Bytes16 = uint8_t __attribute__((vector_size(16)));

inline Bytes16 loadBytes(const uint8_t* p) {
    Bytes16 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline Bytes16 minBytes(Bytes16 a, Bytes16 b) { return a < b ? a : b; }

// The same operations on one byte or 16, so that a row kernel is written once (see forEachLane).
inline uint8_t load(const uint8_t* p, uint8_t) { return *p; }
inline Bytes16 load(const uint8_t* p, Bytes16) { return loadBytes(p); }
inline void store(uint8_t* p, uint8_t v) { *p = v; }
inline void store(uint8_t* p, Bytes16 v) { std::memcpy(p, &v, sizeof v); }
inline uint8_t splat(uint8_t v, uint8_t) { return v; }
inline Bytes16 splat(uint8_t v, Bytes16) { return Bytes16{} + v; }
// mask ? a : b, lane by lane (mask from comparing lanes: a bool for one byte, all ones or zeros for 16).
inline uint8_t select(bool mask, uint8_t a, uint8_t b) { return mask ? a : b; }
template <typename Mask>
inline Bytes16 select(Mask mask, Bytes16 a, Bytes16 b) { return mask ? a : b; }
inline uint8_t minOf(uint8_t a, uint8_t b) { return std::min(a, b); }
inline Bytes16 minOf(Bytes16 a, Bytes16 b) { return minBytes(a, b); }
// 1 + a, capped at 255 (the distance cap).
inline uint8_t plusOne(uint8_t a) { return uint8_t(a + (a != 255)); }
inline Bytes16 plusOne(Bytes16 a) { return a - (Bytes16)(a != 255); }  // a true lane is all ones, i.e. -1

// body(k, T{}) for k < n: 16 lanes at a time (T = Bytes16), then one at a time (T = uint8_t). body must only
// read what it does not write, so that lanes are independent.
template <typename Body>
inline void forEachLane(std::size_t n, Body body) {
    std::size_t k = 0;
    for (; k + 16 <= n; k += 16) body(k, Bytes16{});
    for (; k < n; ++k) body(k, uint8_t{});
}

// 0xFF where a[k] == b[k], else 0, for 16 labels.
inline Bytes16 equalLabels(const uint32_t* a, const uint32_t* b) {
#if defined(__SSE2__)
    __m128i m[4];
    for (int q = 0; q < 4; ++q)
        m[q] = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(a + 4 * q)),
                               _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + 4 * q)));
    const __m128i packed = _mm_packs_epi16(_mm_packs_epi32(m[0], m[1]), _mm_packs_epi32(m[2], m[3]));
    Bytes16 out;
    std::memcpy(&out, &packed, sizeof out);
    return out;
#else
    Bytes16 out;
    for (int q = 0; q < 16; ++q) out[q] = a[q] == b[q] ? 0xFF : 0;
    return out;
#endif
}
// dst[c * dstStride + r] = src[r * srcStride + c] for r < rows, c < cols: 16 x 16 tiles in registers (four rounds
// of interleaving rows i and i + 8 transpose a tile), the edges one byte at a time.
inline void transposeBytes(const uint8_t* src, std::size_t srcStride, uint8_t* dst, std::size_t dstStride, int rows,
                           int cols) {
    int r0 = 0;
#if defined(__SSE2__)
    for (; r0 + 16 <= rows; r0 += 16) {
        int c0 = 0;
        for (; c0 + 16 <= cols; c0 += 16) {
            // Fully unrolled, so that the tile stays in registers.
            __m128i a[16], t[16];
#pragma GCC unroll 16
            for (int i = 0; i < 16; ++i)
                a[i] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + (r0 + i) * srcStride + c0));
#pragma GCC unroll 4
            for (int round = 0; round < 4; ++round) {
#pragma GCC unroll 8
                for (int i = 0; i < 8; ++i) {
                    t[2 * i] = _mm_unpacklo_epi8(a[i], a[i + 8]);
                    t[2 * i + 1] = _mm_unpackhi_epi8(a[i], a[i + 8]);
                }
#pragma GCC unroll 16
                for (int i = 0; i < 16; ++i) a[i] = t[i];
            }
#pragma GCC unroll 16
            for (int i = 0; i < 16; ++i)
                _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + (c0 + i) * dstStride + r0), a[i]);
        }
        for (int r = r0; r < r0 + 16; ++r)
            for (int c = c0; c < cols; ++c) dst[c * dstStride + r] = src[r * srcStride + c];
    }
#endif
    for (int r = r0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) dst[c * dstStride + r] = src[r * srcStride + c];
}

inline uint8_t equalLabels(const uint32_t* a, const uint32_t* b, uint8_t) { return *a == *b ? 0xFF : 0; }
inline Bytes16 equalLabels(const uint32_t* a, const uint32_t* b, Bytes16) { return equalLabels(a, b); }

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

// Bit q set where p[q] != 0, for q < 16.
inline unsigned nonzeroBits(const uint8_t* p) {
#if defined(__SSE2__)
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    return ~unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128()))) & 0xFFFF;
#else
    unsigned bits = 0;
    for (int q = 0; q < 16; ++q) bits |= unsigned(p[q] != 0) << q;
    return bits;
#endif
}

// f(k) for every k < n with p[k] != 0, skipping zeros 16 at a time: for sparse work without a branch per byte.
template <typename F>
inline void forEachNonzero(const uint8_t* p, int n, F f) {
    int k = 0;
    for (; k + 16 <= n; k += 16)
        for (unsigned bits = nonzeroBits(p + k); bits; bits &= bits - 1) f(k + std::countr_zero(bits));
    for (; k < n; ++k)
        if (p[k]) f(k);
}

}  // namespace vr
