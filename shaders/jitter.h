// Jitter (docs/ALGORITHMS.md section 1): each ray's lattice starts a per-pixel fraction of a step after its entry,
// so that the lattices of neighbouring rays no longer line up with the grid's slices, which trades the wood-grain
// rings of a shared lattice for fine noise (VTK's jittering). Stated once: the CPU reference reads this file in
// double, the casters in float (shared_language.h); the fraction itself is exact in both.
#ifndef VR_JITTER_H
#define VR_JITTER_H

#include "shared_language.h"

#ifdef __cplusplus
#include "glsl_layout_types.h"
namespace vr::device {
#endif

// A 32-bit integer hash with good avalanche (two multiply-xorshift rounds), wrapping in both languages.
VR_FUNCTION uint jitterHash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The fraction of a step in [0, 1) by which pixel (px, py)'s lattice starts late: the hash's top 24 bits over 2^24,
// exact in float, so the device and the CPU reference start every ray at the same fraction.
VR_FUNCTION VR_REAL jitterFraction(uint px, uint py) {
    return VR_REAL(jitterHash(px ^ jitterHash(py)) >> 8u) / VR_REAL(16777216);
}

// The start of a jittered lattice: `fraction` of a step dt after the interval's entry (the exit stays).
VR_FUNCTION VR_REAL jitteredEntry(VR_REAL tEntry, VR_REAL dt, VR_REAL fraction) {
    VR_PRECISE VR_REAL t = tEntry + fraction * dt;
    return t;
}

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif
