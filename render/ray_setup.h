// Ray setup shared by every caster (docs/ALGORITHMS.md sections 1 and 5): world ray -> grid ray, the volume
// interval, the sampling lattice, the voxel of a sample and the leap count n of each caster. The math is
// shaders/ray_math.h's, which the casters compile in float; here it is double, with the CPU reference's types.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

#include "render/camera.h"
#include "core/distance_fields.h"
#include "core/errors.h"
#include "core/grid.h"
#include "shaders/clip_planes.h"
#include "shaders/device_contract.h"
#include "shaders/jitter.h"
#include "shaders/ray_math.h"

namespace vr {

// A ray in grid coordinates: o_g = (o_w - origin) / h, d_g = d_w / h, NOT renormalised, so that the
// parameter t is the world distance along the (unit) world ray in both spaces.
struct GridRay {
    Vec3d o, d;
    Vec3d at(double t) const { return o + d * t; }
};

inline GridRay toGridRay(const Ray& ray, const GridGeometry& grid) {
    return {(ray.origin - grid.origin) / grid.spacing, ray.direction / grid.spacing};
}

// The part of a ray inside the grid box [0, N]: samples live in [tEntry, tExit).
struct RayInterval {
    double tEntry = 0, tExit = 0;
    bool empty() const { return !(tEntry < tExit); }
};

// Slab test against the box [lo, hi] of grid coordinates (device::clipSlab per axis). tEntry is clamped to >= 0
// so that a camera inside the volume starts at its eye.
inline RayInterval intersectBox(const GridRay& r, const Vec3i& lo, const Vec3i& hi) {
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    bool outside = false;
    for (int a = 0; a < 3; ++a) device::clipSlab(r.o[a], r.d[a], lo[a], hi[a], t0, t1, outside);
    if (outside || !(t0 < t1)) return {0, 0};
    return {t0, t1};
}

// The grid box [0, N].
inline RayInterval intersectGrid(const GridRay& r, const Vec3i& dims) { return intersectBox(r, {0, 0, 0}, dims); }

// What clips every ray of a render, in grid coordinates: the crop box's faces (voxels lo..hi cover [lo, hi + 1];
// the grid [0, N] without a crop) and the planes, each keeping dot(normal, p) >= offset. A world plane
// dot(n, x) >= d becomes dot(n h, p) >= d - dot(n, origin), since x = origin + h p.
struct RayClip {
    Vec3i lo, hi;
    std::vector<ClipPlane> planes;

    static RayClip of(const GridGeometry& grid, const RenderSettings& settings) {
        RayClip clip{{0, 0, 0}, grid.dims, {}};
        if (settings.crop) {
            clip.lo = settings.crop->lo;
            clip.hi = settings.crop->hi + Vec3i{1, 1, 1};
        }
        for (const ClipPlane& p : settings.clipPlanes)
            clip.planes.push_back({p.normal * grid.spacing, p.offset - dot(p.normal, grid.origin)});
        return clip;
    }
};

// The ray's interval in the crop box, clipped by every plane (shaders/clip_planes.h; the casters' intersectGrid in
// shaders/ray_setup.glsl): its samples lie on the kept side of each, and a leap, which never passes tExit, never
// crosses one.
inline RayInterval clipInterval(const GridRay& r, const RayClip& clip) {
    RayInterval iv = intersectBox(r, clip.lo, clip.hi);
    for (const ClipPlane& p : clip.planes) {
        const double s = p.offset - dot(p.normal, r.o), q = dot(p.normal, r.d);
        iv.tEntry = device::clipEntry(iv.tEntry, s, q);
        iv.tExit = device::clipExit(iv.tExit, s, q);
    }
    if (iv.empty()) return {0, 0};
    return iv;
}

// Jitter: the entry moved `fraction` of a step later (shaders/jitter.h jitterFraction), the exit kept; an interval
// this empties is empty. The casters' jitteredInterval in shaders/ray_setup.glsl.
inline RayInterval jitteredInterval(RayInterval iv, double dt, double fraction) {
    if (iv.empty()) return iv;
    iv.tEntry = device::jitteredEntry(iv.tEntry, dt, fraction);
    return iv.empty() ? RayInterval{0, 0} : iv;
}

// Lattice indices are exact in double below 2^53 (the shaders count in double) and latticeCount() corrects its
// estimate one sample at a time: with a step so small that a ray across the grid takes more than 2^52 samples it
// would never finish. Renderers refuse such steps before casting (host only: no GLSL counterpart).
inline void requireLatticeFits(const GridGeometry& grid, double stepVoxels) {
    if (length(grid.extent()) / (stepVoxels * grid.smallestSpacing()) <= 0x1p52) return;
    char text[160];
    std::snprintf(text, sizeof text, "--step %g: too small for this volume (a ray across it would take more than "
                  "2^52 samples of %g x its smallest spacing %g)", stepVoxels, stepVoxels, grid.smallestSpacing());
    throw InputError(text);
}

// The lattice t_k = tEntry + k dt, shared by every caster. Positions are recomputed from k, never accumulated.
inline double latticeT(const RayInterval& iv, double dt, int64_t k) { return device::latticeT(iv.tEntry, dt, k); }

// Number of lattice samples with t_k < tExit (exactly as the comparison decides it, not as the division rounds).
inline int64_t latticeCount(const RayInterval& iv, double dt) { return device::latticeCount(iv.tEntry, iv.tExit, dt); }

// The voxel holding a grid position, before clamping (may be outside [0, N) by rounding at the box faces).
inline Vec3i floorVoxel(const Vec3d& p) {
    return {int(std::floor(p.x)), int(std::floor(p.y)), int(std::floor(p.z))};
}
inline Vec3i clampVoxel(const Vec3i& v, const Vec3i& dims) {
    return {std::clamp(v.x, 0, dims.x - 1), std::clamp(v.y, 0, dims.y - 1), std::clamp(v.z, 0, dims.z - 1)};
}
// The voxel of the sample at t: floor(o_g + t d_g) clamped into the crop box, [0, N) without a crop. A sample on a
// face, which rounding may put either side of it, is taken from the voxel inside.
inline Vec3i sampleVoxel(const GridRay& r, double t, const RayClip& clip) {
    const Vec3i v = floorVoxel(r.at(t));
    return {std::clamp(v.x, clip.lo.x, clip.hi.x - 1), std::clamp(v.y, clip.lo.y, clip.hi.y - 1),
            std::clamp(v.z, clip.lo.z, clip.hi.z - 1)};
}

// Octants are numbered as the device numbers them; the preprocessor builds each octant's field by core's numbering.
static_assert([] {
    for (int oct = 0; oct < kOctants; ++oct)
        for (int a = 0; a < 3; ++a)
            if (device::octantSign(oct, a) != octantSign(oct, a)) return false;
    return true;
}());

inline int rayOctant(const GridRay& r) { return device::octantOf(r.d.x, r.d.y, r.d.z); }

// An inclusive range of voxels: the region a leap may cover.
struct VoxelBox {
    Vec3i lo, hi;
};

// PC: the Chebyshev ball of radius r about v.
inline VoxelBox chebyshevBall(const Vec3i& v, int r) {
    return {{v.x - r, v.y - r, v.z - r}, {v.x + r, v.y + r, v.z + r}};
}

// ACD / EACD: the box {v + s*e : 0 <= e_a < ext_a} of octant oct (ACD: ext = (k, k, k)).
inline VoxelBox octantBox(const Vec3i& v, int oct, const Vec3i& ext) {
    VoxelBox b;
    for (int a = 0; a < 3; ++a) {
        const int far = v[a] + device::octantSign(oct, a) * (ext[a] - 1);
        b.lo[a] = std::min(v[a], far);
        b.hi[a] = std::max(v[a], far);
    }
    return b;
}

// Whether a frame's leaps take the samples their margin proves, unchecked (docs/ALGORITHMS.md section 8): where the
// margin is at most 1/64 of a step for every ray (its farthest t at most the distance from the eye to the grid's
// farthest corner), so that it costs a sample at a box's face only rarely. The casters then skip the check of the
// last sample's position, which every leap's count waited on (10-13 % of an EACD frame on lavapipe). Tiny steps keep
// the check: there the margin is many samples, and each box's face would be crossed one sample at a time.
inline bool leapsByTheMargin(const GridGeometry& grid, const Camera& camera, double dt) {
    double farthest = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3d c{corner & 1 ? 1.0 : 0.0, corner & 2 ? 1.0 : 0.0, corner & 4 ? 1.0 : 0.0};
        farthest = std::max(farthest, length(grid.origin + c * grid.extent() - camera.eye));
    }
    return 64 * device::leapLatticeSlack(farthest) <= dt;
}

// What a leap subtracts from the distance to its box's faces where the frame leaps by the margin (device::
// leapLatticeSlack and the others, in double); none elsewhere, where the CPU reference counts exactly.
struct LeapSlack {
    Vec3d boxExit{0, 0, 0};  // per axis (0 on an axis the ray does not move along)
    double ball = 0;
};

inline LeapSlack leapSlack(const GridRay& r, const RayInterval& iv, const Vec3i& dims) {
    const Vec3d speed = abs(r.d);
    const double lattice = device::leapLatticeSlack(iv.tExit);
    LeapSlack s;
    for (int a = 0; a < 3; ++a) s.boxExit[a] = device::leapAxisSlack(lattice, dims[a], speed[a]);
    s.ball = device::leapBallSlack(lattice, maxComponent(dims), maxComponent(speed));
    return s;
}

// PC: the samples that stay in the Chebyshev ball of radius r, less the slack (device::pcLeapSamples). Returned as a
// double: it may exceed any integer when dt is tiny; leapCount() bounds it.
inline double pcLeapSamples(int r, double dt, const GridRay& ray, const LeapSlack& slack = {}) {
    return device::pcLeapSamples(r, maxComponent(abs(ray.d)), dt, slack.ball);
}

// ACD / EACD: the t at which the ray leaves the box through its far faces (device::boxAxisExitT per axis), each
// moved closer by its slack. An axis with d_a == 0 never limits the box (+inf, never 0/0).
inline double boxExitT(const GridRay& ray, const Vec3i& v, int oct, const Vec3i& ext,
                       const LeapSlack& slack = {}) {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
        if (ray.d[a] != 0)
            t = std::min(t, device::boxAxisExitT(v[a], device::octantSign(oct, a), ext[a], ray.o[a], ray.d[a]) -
                                slack.boxExit[a]);
    return t;
}

using device::boxLeapSamples;

// Trilinear sampling steps a single-voxel box sample by sample (device::trilinearLeapSamples).
inline double trilinearLeapSamples(double wanted, const VoxelBox& box) {
    return device::trilinearLeapSamples(wanted, box.lo == box.hi);
}

// Whether the sample at t lies in `box` as floorVoxel places it, given that the span's first sample does (its
// voxel is the box's corner v): positions only grow along an axis the ray climbs and only shrink along one it
// descends (every rounding is monotone), so the far face of each axis is the only one a later sample can cross.
inline bool beforeFarFaces(const GridRay& ray, double t, const VoxelBox& box) {
    const Vec3d p = ray.at(t);
    for (int a = 0; a < 3; ++a)
        if ((ray.d[a] > 0 && p[a] >= double(box.hi[a] + 1)) || (ray.d[a] < 0 && p[a] < double(box.lo[a])))
            return false;
    return true;
}

// The leap actually taken from sample k (of kCount), wanting `wanted` samples inside `box` (which holds sample
// k's voxel): never past the volume exit, and never to a sample whose floor voxel rounding put outside the box.
// Positions are monotone in t per axis, so checking the last sample of the span checks all of them. Always >= 1.
inline int64_t leapCount(const GridRay& ray, const RayInterval& iv, double dt, int64_t k, int64_t kCount,
                         double wanted, const VoxelBox& box) {
    int64_t n = int64_t(std::min(wanted, double(kCount - k)));
    while (n > 1 && !beforeFarFaces(ray, latticeT(iv, dt, k + n - 1), box)) --n;
    return std::max<int64_t>(n, 1);
}

}  // namespace vr
