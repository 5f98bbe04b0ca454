// The blends other than composite (docs/ALGORITHMS.md section 11) and their leap, stated once: the CPU reference
// reads this file in double, the casters in float (shared_language.h). A ray folds each sample's scalar into a
// running value (the largest, the smallest, the sum) or, for the iso-surface, into the side of the iso-value it lies
// on; the blocks caster leaps over a block of the volume whenever the block's scalar range (its voxels and their
// trilinear footprints: render/block_extrema.h) shows that none of its samples can change the ray's result.
#ifndef VR_BLEND_H
#define VR_BLEND_H

#include "device_contract.h"

#ifdef __cplusplus
namespace vr::device {
#endif

// Edge of the blocks whose scalar range the blocks caster reads, in voxels.
VR_CONSTANT int kBlockSize = 8;

// Bisections of the interval between the last sample before an iso-surface and the first beyond it: the hit lies
// within dt 2^-(kIsoBisections + 1) of the surface of the interpolated scalar.
VR_CONSTANT int kIsoBisections = 12;

// The side of the iso-value a scalar lies on: inside at or above it.
VR_FUNCTION bool isoInside(VR_REAL scalar, VR_REAL isoValue) { return scalar >= isoValue; }

// Whether no sample in a block whose scalars lie in [lo, hi] can change the ray's result, given the running value
// (MIP: the largest scalar so far; MinIP: the smallest) and, for the iso-surface, the side of the last sample: such a
// block is leapt over whole. Exact: MIP skips a block that cannot raise the maximum, MinIP one that cannot lower the
// minimum, the iso-surface one that lies wholly on the ray's side (the crossing cannot be inside it), and average
// one of a single value, whose n samples add n times it.
VR_FUNCTION bool blockSkipped(int blend, VR_REAL lo, VR_REAL hi, VR_REAL running, VR_REAL isoValue, bool inside) {
    if (blend == kBlendMIP) return hi <= running;
    if (blend == kBlendMinIP) return lo >= running;
    if (blend == kBlendAverage) return lo == hi;
    if (blend == kBlendIso) return inside ? isoInside(lo, isoValue) : !isoInside(hi, isoValue);
    return false;
}

// The box extent along one axis, from voxel v to the far face of its block in the direction `sign` of the ray
// (octantBox's ext: the voxels from v to the block's last one that way, v's included).
VR_FUNCTION int blockExtent(int v, int sign) {
    int first = v - v % kBlockSize;
    return sign > 0 ? first + kBlockSize - v : v - first + 1;
}

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif
