// Ray setup shared by every caster, in float (docs/ALGORITHMS.md section 8): shaders/ray_math.h's math on the
// casters' parameters and GLSL types, as render/ray_setup.h and Camera::ray() put it in double. Every caster computes
// a sample's position from its lattice index with one expression (samplePosition), so at thresholds 0 they all fetch
// the same voxels; a leap counts only samples that lie in its box as that expression rounds them. `precise` forbids
// fused multiply-adds, which would let the compiler round one call site differently from another.
#ifndef VR_RAY_SETUP_GLSL
#define VR_RAY_SETUP_GLSL

#include "caster_params.glsl"
#include "clip_planes.h"
#include "jitter.h"
#include "ray_math.h"

struct GridRay {
    vec3 o, d;
};

struct RayInterval {
    float tEntry, tExit;
};

// Camera::ray() for the pixel centre (px, py), then toGridRay().
GridRay cameraGridRay(float px, float py, out vec3 worldDirection) {
    precise float u = imagePlaneU(px, params.imageSize.x, params.imageSize.y, params.halfHeight) + params.frustumShift;
    float v = imagePlaneV(py, params.imageSize.y, params.halfHeight);
    precise vec3 origin, direction;
    if (!PERSPECTIVE) {  // the including shader's specialization constant (caster.comp)
        origin = params.eye.xyz + params.right.xyz * u + params.up.xyz * v;
        direction = params.forward.xyz;
    } else {
        precise vec3 w = params.forward.xyz + params.right.xyz * u + params.up.xyz * v;
        precise float len = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        origin = params.eye.xyz;
        direction = w / len;
    }
    worldDirection = direction;
    GridRay r;
    r.o = (origin - params.gridOrigin.xyz) / params.spacing.xyz;
    r.d = direction / params.spacing.xyz;
    return r;
}

vec3 rayAt(GridRay r, float t) {
    precise vec3 p = r.o + r.d * t;
    return p;
}

// RayClip's interval (render/ray_setup.h clipInterval): the crop box (the grid without a crop), then every plane.
// The slabs are written out per axis: llvmpipe runs every loop's body for all invocations of a SIMD batch.
RayInterval intersectGrid(GridRay r) {
    float t0 = 0.0, t1 = kInfinity;
    bool outside = false;
    clipSlab(r.o.x, r.d.x, params.cropLo.x, params.cropHi.x, t0, t1, outside);
    clipSlab(r.o.y, r.d.y, params.cropLo.y, params.cropHi.y, t0, t1, outside);
    clipSlab(r.o.z, r.d.z, params.cropLo.z, params.cropHi.z, t0, t1, outside);
    for (int i = 0; i < params.clipPlaneCount; ++i) {
        vec4 plane = params.clipPlanes[i];
        precise float s = plane.w - dot(plane.xyz, r.o);
        precise float q = dot(plane.xyz, r.d);
        t0 = clipEntry(t0, s, q);
        t1 = clipExit(t1, s, q);
    }
    if (outside || !(t0 < t1)) return RayInterval(0.0, 0.0);
    return RayInterval(t0, t1);
}

bool intervalEmpty(RayInterval iv) { return !(iv.tEntry < iv.tExit); }

// With jitter, the entry moved pixel's fraction of a step later, the exit kept (render/ray_setup.h
// jitteredInterval); an interval this empties is empty.
RayInterval jitteredInterval(RayInterval iv, ivec2 pixel) {
    if (params.jitter == 0 || intervalEmpty(iv)) return iv;
    float entry = jitteredEntry(iv.tEntry, params.dt, jitterFraction(uint(pixel.x), uint(pixel.y)));
    return entry < iv.tExit ? RayInterval(entry, iv.tExit) : RayInterval(0.0, 0.0);
}

// The lattice t_k = tEntry + k dt (k is exact in float below 2^24; beyond, t_k stays monotone in k).
float latticeT(RayInterval iv, uint k) { return latticeT(iv.tEntry, params.dt, k); }

// The one position expression of the lattice rule: sample k of the ray.
vec3 samplePosition(GridRay r, RayInterval iv, uint k) { return rayAt(r, latticeT(iv, k)); }

uint latticeCount(RayInterval iv) { return latticeCount(iv.tEntry, iv.tExit, params.dt); }

// The first of the ray's kCount samples at or beyond t (kCount: none; t lies beyond its exit).
uint firstSampleFrom(RayInterval iv, float t, uint kCount) {
    return t < iv.tExit ? min(latticeCount(iv.tEntry, t, params.dt), kCount) : kCount;
}

ivec3 floorVoxel(vec3 p) { return ivec3(floor(p)); }
ivec3 clampVoxel(ivec3 v) { return clamp(v, ivec3(0), params.dims.xyz - 1); }
// Clamped into the crop box (the grid without a crop), as RayClip::sampleVoxel in render/ray_setup.h.
ivec3 sampleVoxel(GridRay r, RayInterval iv, uint k) {
    return clamp(floorVoxel(samplePosition(r, iv, k)), params.cropLo.xyz, params.cropHi.xyz - 1);
}

int rayOctant(GridRay r) { return octantOf(r.d.x, r.d.y, r.d.z); }

// What a leap subtracts from the distance to its box's faces (ray_math.h leapLatticeSlack and the others).
struct LeapSlack {
    vec3 boxExit;  // per axis, for the ACD / EACD boxes (0 on an axis the ray does not move along)
    float ball;    // for the PC ball, whose radius every axis shares
};

LeapSlack leapSlack(GridRay r, RayInterval iv) {
    vec3 speed = abs(r.d);
    float lattice = leapLatticeSlack(iv.tExit);
    LeapSlack s;
    s.boxExit = vec3(leapAxisSlack(lattice, params.dims.x, speed.x), leapAxisSlack(lattice, params.dims.y, speed.y),
                     leapAxisSlack(lattice, params.dims.z, speed.z));
    s.ball = leapBallSlack(lattice, max(max(params.dims.x, params.dims.y), params.dims.z),
                           max(max(speed.x, speed.y), speed.z));
    return s;
}

struct VoxelBox {
    ivec3 lo, hi;
};

VoxelBox chebyshevBall(ivec3 v, int r) { return VoxelBox(v - r, v + r); }

VoxelBox octantBox(ivec3 v, int oct, ivec3 ext) {
    VoxelBox b;
    for (int a = 0; a < 3; ++a) {
        int far = v[a] + octantSign(oct, a) * (ext[a] - 1);
        b.lo[a] = min(v[a], far);
        b.hi[a] = max(v[a], far);
    }
    return b;
}

// PC: the samples in the ball of radius r; slack: 0 or the ball's.
float pcLeapSamples(int r, GridRay ray, float slack) {
    return pcLeapSamples(r, max(max(abs(ray.d.x), abs(ray.d.y)), abs(ray.d.z)), params.dt, slack);
}

// ACD / EACD: per axis, the t at which the ray leaves the box through its far face (+inf on an axis the ray does
// not move along).
vec3 boxExitsT(GridRay ray, ivec3 v, int oct, ivec3 ext) {
    vec3 t = vec3(kInfinity);
    for (int a = 0; a < 3; ++a)
        if (ray.d[a] != 0.0) t[a] = boxAxisExitT(v[a], octantSign(oct, a), ext[a], ray.o[a], ray.d[a]);
    return t;
}

// ACD / EACD: the samples before the nearest of the box's exits, each moved closer by slack (0 or leapSlack's).
float boxLeapSamples(vec3 exits, vec3 slack, float t) {
    precise vec3 closer = exits - slack;
    return boxLeapSamples(min(min(closer.x, closer.y), closer.z), t, params.dt);
}

float trilinearLeapSamples(float wanted, VoxelBox box) { return trilinearLeapSamples(wanted, box.lo == box.hi); }

bool inBox(ivec3 v, VoxelBox box) { return all(greaterThanEqual(v, box.lo)) && all(lessThanEqual(v, box.hi)); }

// The leap taken from sample k of kCount, which lies in `box`: the samples wanted with the margin, which provably lie
// in it, where the frame leaps by the margin alone (MARGIN_LEAPS, docs/ALGORITHMS.md section 8); else the samples
// wanted without it when the last of them lies in the box as samplePosition places it (positions are monotone, so
// then all of them do), and those with the margin otherwise. Never past the volume exit; always >= 1.
uint leapCount(GridRay ray, RayInterval iv, uint k, uint kCount, float wanted, float wantedWithMargin, VoxelBox box) {
    uint margin = min(uint(clamp(wantedWithMargin, 1.0, 2147483648.0)), kCount - k);
    if (MARGIN_LEAPS) return margin;
    uint n = min(uint(clamp(wanted, 1.0, 2147483648.0)), kCount - k);
    return n > 1u && !inBox(sampleVoxel(ray, iv, k + n - 1u), box) ? margin : n;
}

#endif
