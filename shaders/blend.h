// The blends other than composite (docs/ALGORITHMS.md section 11) and their leap, stated once: the CPU reference
// reads this file in double, the casters in float (shared_language.h). A ray folds each sample's scalar into a
// running value (the largest, the smallest, the sum) or, for the iso-surface, into the side of the iso-value it lies
// on; the blocks caster leaps over a block of the volume whenever the block's scalar range (its voxels and their
// trilinear footprints: render/block_extrema.h) shows that none of its samples can change the ray's result. The
// block boxes are the hier caster's too (composite, docs/ALGORITHMS.md section 10).
#ifndef VR_BLEND_H
#define VR_BLEND_H

#include "device_contract.h"

#ifdef __cplusplus
namespace vr::device {
#endif

// Edge of the finest blocks whose scalar range the blocks caster reads, in voxels, and the levels of coarser blocks
// above them, each block of a level the union of 2 x 2 x 2 of the level below (4, 8, 16 and 32 voxels). At a new
// block the caster leaps over the coarsest block that cannot change the result, else steps sample by sample to the
// finest block's far faces.
VR_CONSTANT int kBlockShift = 2;
VR_CONSTANT int kBlockSize = 1 << kBlockShift;
VR_CONSTANT int kBlockLevels = 4;

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

// MIP and MinIP: the running value has reached a scalar beyond which the transfer table classifies every value
// alike (render/flat_table_ends.h), so no later sample can change the pixel and the ray ends.
VR_FUNCTION bool runningSettled(int blend, VR_REAL running, VR_REAL flatAbove, VR_REAL flatBelow) {
    return (blend == kBlendMIP && running >= flatAbove) || (blend == kBlendMinIP && running <= flatBelow);
}

// MIP and MinIP: the running value before the ray's first sample. Every value below flatBelow shows as flatBelow
// does (render/flat_table_ends.h), so MIP starts there, not at -inf, and MinIP at flatAbove: the pixel is the same,
// and a block that lies wholly in the flat run (noisy air under a TF transparent there) is leapt over.
VR_FUNCTION VR_REAL initialRunning(int blend, VR_REAL flatAbove, VR_REAL flatBelow) {
    return blend == kBlendMIP ? flatBelow : flatAbove;
}

// The running value after a scalar: MIP's largest, MinIP's smallest (the other blends keep none).
VR_FUNCTION VR_REAL foldRunning(int blend, VR_REAL running, VR_REAL scalar) {
    if (blend == kBlendMIP) return scalar > running ? scalar : running;
    if (blend == kBlendMinIP) return scalar < running ? scalar : running;
    return running;
}

// MIP and MinIP: the blends that keep a running extreme (they start, probe, settle and end a sampled block early).
VR_FUNCTION bool keepsExtreme(int blend) { return blend == kBlendMIP || blend == kBlendMinIP; }

// MIP and MinIP with the blocks caster fold kProbes samples of the ray into their starting value, at lattice indices
// i kCount / (kProbes + 1): values the ray has, so that a block that cannot pass them is leapt over from the start.
// The result, the running value, is the primitive caster's exactly: the largest sample is sampled, or lies in a
// block that could not pass the running value.
VR_CONSTANT int kProbes = 3;
VR_FUNCTION uint probeSample(int i, uint kCount) { return uint(i + 1) * kCount / uint(kProbes + 1); }

// The box extent along one axis, from voxel v >= 0 to the far face of its block of `size` voxels (a power of two) in
// the direction `sign` of the ray (octantBox's ext: the voxels from v to the block's last one that way, v's
// included). A mask, not a remainder: llvmpipe divides lane by lane.
VR_FUNCTION int blockExtent(int v, int sign, int size) {
    int first = v & ~(size - 1);
    return sign > 0 ? first + size - v : v - first + 1;
}

// The hier caster (docs/ALGORITHMS.md section 10): the box extent along one axis from voxel v to the far face of a
// box of `blocks` blocks of 2^shift voxels, the first of them v's own, in the direction `sign`.
VR_FUNCTION int blockBoxExtent(int v, int sign, int shift, int blocks) {
    return blockExtent(v, sign, 1 << shift) + ((blocks - 1) << shift);
}

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif
