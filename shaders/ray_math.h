// The ray math of every caster, stated once (docs/ALGORITHMS.md sections 1, 5, 6 and 8): the pixel's image-plane
// coordinates, the slab test, the sampling lattice, the leap counts, span opacity, the termination count and the
// Phong shade. The CPU reference compiles it in double, the casters in float (shared_language.h); the callers only
// carry their own vector types in and out (render/ray_setup.h, render/span.h, shaders/ray_setup.glsl,
// shaders/span.glsl). VR_PRECISE keeps glslang from fusing a multiply-add, which would let one call site round
// differently from another.
#ifndef VR_RAY_MATH_H
#define VR_RAY_MATH_H

#include "shared_language.h"

#ifdef __cplusplus
namespace vr::device {
#else
#include "numerics.glsl"  // vrExpm1 and kInfinity, which C++ takes from its library
#endif

// Image-plane coordinates of the pixel point (px, py) of a width x height image: (0, 0) is the top-left corner,
// the image centre maps to (0, 0), and the plane spans halfHeight above and below it (Camera::ray).
VR_FUNCTION VR_REAL imagePlaneU(VR_REAL px, int width, int height, VR_REAL halfHeight) {
    VR_PRECISE VR_REAL aspect = VR_REAL(width) / VR_REAL(height);
    VR_PRECISE VR_REAL u = (VR_REAL(2) * px / VR_REAL(width) - VR_REAL(1)) * halfHeight * aspect;
    return u;
}
VR_FUNCTION VR_REAL imagePlaneV(VR_REAL py, int height, VR_REAL halfHeight) {
    VR_PRECISE VR_REAL v = (VR_REAL(1) - VR_REAL(2) * py / VR_REAL(height)) * halfHeight;
    return v;
}

// Slab test of one axis of the box [lo, hi] for the grid ray o + t d, narrowing [t0, t1]. An axis with d == 0
// never limits t; the ray is then outside unless lo <= o < hi (half-open like the voxels: a ray lying on the far
// face samples no voxel). Without a loop or an early return: llvmpipe neither unrolls a loop that returns nor skips
// the code after a return.
VR_FUNCTION void clipSlab(VR_REAL o, VR_REAL d, int lo, int hi, VR_INOUT(VR_REAL) t0, VR_INOUT(VR_REAL) t1,
                          VR_INOUT(bool) outside) {
    bool parallel = d == VR_REAL(0);
    VR_PRECISE VR_REAL ta = parallel ? VR_REAL(0) : (VR_REAL(lo) - o) / d;
    VR_PRECISE VR_REAL tb = parallel ? VR_REAL(0) : (VR_REAL(hi) - o) / d;
    outside = outside || (parallel && !(o >= VR_REAL(lo) && o < VR_REAL(hi)));
    t0 = parallel ? t0 : max(t0, min(ta, tb));
    t1 = parallel ? t1 : min(t1, max(ta, tb));
}

// The lattice t_k = tEntry + k dt, shared by every caster: positions are recomputed from k, never accumulated.
VR_FUNCTION VR_REAL latticeT(VR_REAL tEntry, VR_REAL dt, VR_INDEX k) {
    VR_PRECISE VR_REAL t = tEntry + VR_REAL(k) * dt;
    return t;
}

// Number of lattice samples with t_k < tExit, exactly as the comparison decides it, not as the division rounds
// (t_k is monotone in k).
VR_MATH_FUNCTION VR_INDEX latticeCount(VR_REAL tEntry, VR_REAL tExit, VR_REAL dt) {
    if (!(tEntry < tExit)) return VR_INDEX(0);
    VR_PRECISE VR_REAL q = (tExit - tEntry) / dt;
    VR_INDEX k = VR_INDEX(max(VR_REAL(1), ceil(q)));
    while (k > VR_INDEX(1) && latticeT(tEntry, dt, k - VR_INDEX(1)) >= tExit) --k;
    while (latticeT(tEntry, dt, k) < tExit) ++k;
    return k;
}

// The first sample of piece `piece` of a ray's kCount samples cut into `pieces` of nearly equal length:
// kCount piece / pieces rounded down, without the product (which could overflow the index).
VR_FUNCTION VR_INDEX pieceStart(VR_INDEX kCount, VR_INDEX piece, VR_INDEX pieces) {
    return kCount / pieces * piece + kCount % pieces * piece / pieces;
}

// What a leap subtracts from the distance to its box's faces (world units), so that the last sample it counts lies
// inside the box as the casters' float positions round it (docs/ALGORITHMS.md section 8). With u = 2^-24 (float's
// unit roundoff), T the ray's largest t and N_a the grid size: t_k is within 3.01 u T of tEntry + k dt, a position
// within 4.01 u T |d_a| + 1.01 u N_a of o_a + t d_a, and a box exit and the leap's division add 5.03 u T; the slacks
// take 16 u T and twice the N_a term. The CPU reference takes the same margin in double where the casters leap by it
// alone (leapsByTheMargin), so that both leap alike.
VR_FUNCTION VR_REAL leapLatticeSlack(VR_REAL tExit) {
    VR_PRECISE VR_REAL s = VR_REAL(16) / VR_REAL(16777216) * tExit;
    return s;
}
// ACD / EACD boxes, per axis (0 on an axis the ray does not move along).
VR_FUNCTION VR_REAL leapAxisSlack(VR_REAL lattice, int n, VR_REAL speed) {
    VR_PRECISE VR_REAL s = lattice + VR_REAL(2) / VR_REAL(16777216) * VR_REAL(n) / speed;
    return speed == VR_REAL(0) ? VR_REAL(0) : s;
}
// The PC ball, whose radius every axis shares: the largest N_a and |d_a|.
VR_FUNCTION VR_REAL leapBallSlack(VR_REAL lattice, int largestN, VR_REAL largestSpeed) {
    VR_PRECISE VR_REAL s = lattice + VR_REAL(4) / VR_REAL(16777216) * VR_REAL(largestN) / largestSpeed;
    return s;
}

// PC: the samples t, t + dt, ... t + (n-1) dt stay in the Chebyshev ball of radius r while (n-1) dt speed <= r,
// speed being the ray's largest |d_a|; `slack` (world units) shortens the distance for float rounding (0: none).
VR_MATH_FUNCTION VR_REAL pcLeapSamples(int r, VR_REAL speed, VR_REAL dt, VR_REAL slack) {
    VR_PRECISE VR_REAL q = (VR_REAL(r) / speed - slack) / dt;
    return max(VR_REAL(1), VR_REAL(1) + floor(q));
}

// ACD / EACD: the t at which the ray o + t d (d != 0) leaves the octant box of voxel v along one axis, through the
// far face v + sign (ext - 1) + (sign > 0).
VR_FUNCTION VR_REAL boxAxisExitT(int v, int sign, int ext, VR_REAL o, VR_REAL d) {
    VR_REAL far = VR_REAL(v + sign * (ext - 1) + (sign > 0 ? 1 : 0));
    VR_PRECISE VR_REAL t = (far - o) / d;
    return t;
}

// ACD / EACD: the samples from t strictly before the box's exit t, at least one.
VR_MATH_FUNCTION VR_REAL boxLeapSamples(VR_REAL exitT, VR_REAL t, VR_REAL dt) {
    VR_PRECISE VR_REAL q = (exitT - t) / dt;
    return max(VR_REAL(1), ceil(q));
}

// Trilinear sampling: a leap whose box is the voxel alone may start in a border voxel (a region of its own, thesis
// 4.3.2), inside which the interpolated value changes; such a voxel is stepped sample by sample.
VR_FUNCTION VR_REAL trilinearLeapSamples(VR_REAL wanted, bool singleVoxel) { return singleVoxel ? VR_REAL(1) : wanted; }

// Opacity of a homogeneous span of optical depth sigma L: 1 - exp(-sigma L) without cancellation for a tiny depth
// (in float, 1 - (1 - 1e-8)^n loses everything); exactly 1 for an opaque span.
VR_MATH_FUNCTION VR_REAL spanOpacity(VR_REAL depth) { return -vrExpm1(-depth); }

// Early ray termination belongs to the samples, not to the spans: a span whose samples add sampleDepth = sigma dt
// each stops at the first m with depth + m sampleDepth >= the termination depth, `remaining` being that depth less
// the ray's. The quotient is lowered by `slack` (relative, above the rounding of the caller's depth), so that the
// count is never above m: one short costs one more iteration, one too many would composite a sample that primitive
// stepping never takes. +inf where the span never terminates. The division runs for sampleDepth = 0 too and its
// result is not picked: llvmpipe runs both sides of a branch.
VR_MATH_FUNCTION VR_REAL samplesToTermination(VR_REAL remaining, VR_REAL sampleDepth, VR_REAL slack) {
    VR_PRECISE VR_REAL q = remaining / sampleDepth * (VR_REAL(1) - slack);
    return sampleDepth <= VR_REAL(0) ? kInfinity : max(VR_REAL(1), ceil(q));
}

// Shaded emission of a sample: two-sided Phong with one directional light. toEye: unit vector toward the viewer;
// toLight: unit vector toward the light (a headlight is toEye); normal: unit, or zero for a flat voxel, which gets
// ambient + diffuse with the view vector as normal and no highlight (never normalize(0)).
VR_MATH_FUNCTION VR_VEC3 shade(VR_VEC3 colour, VR_VEC3 normal, VR_VEC3 toEye, VR_VEC3 toLight, VR_REAL ambient,
                          VR_REAL diffuse, VR_REAL specular, VR_REAL shininess) {
    bool isFlat = dot(normal, normal) == VR_REAL(0);
    VR_VEC3 n = isFlat ? toEye : normal;
    if (dot(n, toEye) < VR_REAL(0)) n = -n;
    VR_REAL nl = dot(n, toLight);
    VR_REAL highlight = VR_REAL(0);
    if (!isFlat && nl > VR_REAL(0)) {
        VR_VEC3 reflected = n * (VR_REAL(2) * nl) - toLight;  // unit since n and toLight are
        highlight = pow(max(VR_REAL(0), dot(reflected, toEye)), shininess);
    }
    VR_REAL lit = specular * highlight;
    return colour * (ambient + diffuse * abs(nl)) + VR_VEC3(lit, lit, lit);
}

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif
