// Ray setup shared by every caster: render/ray_setup.h and Camera::ray() in GLSL.
// Positions, the lattice and leap counts are computed in double with the same operations in the same order
// as the CPU reference (`precise` forbids fused multiply-adds), so every sample picks the same voxel even
// where the lattice lands exactly on voxel faces (axis-aligned views). Integer counts are held in doubles
// (exact to 2^53).
#ifndef VR_RAY_SETUP_GLSL
#define VR_RAY_SETUP_GLSL

#include "caster_params.glsl"

const double kInfinity = 1.0LF / 0.0LF;

struct GridRay {
    dvec3 o, d;
};

struct RayInterval {
    double tEntry, tExit;
};

// Camera::ray() for the pixel centre (px, py), then toGridRay().
GridRay cameraGridRay(double px, double py, out dvec3 worldDirection) {
    precise double aspect = double(params.imageSize.x) / double(params.imageSize.y);
    precise double u = (2.0LF * px / double(params.imageSize.x) - 1.0LF) * params.halfHeight * aspect;
    precise double v = (1.0LF - 2.0LF * py / double(params.imageSize.y)) * params.halfHeight;
    precise dvec3 origin, direction;
    if (!PERSPECTIVE) {  // the including shader's specialization constant (caster.comp)
        origin = params.eye.xyz + params.right.xyz * u + params.up.xyz * v;
        direction = params.forward.xyz;
    } else {
        precise dvec3 w = params.forward.xyz + params.right.xyz * u + params.up.xyz * v;
        precise double len = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        origin = params.eye.xyz;
        direction = w / len;
    }
    worldDirection = direction;
    GridRay r;
    r.o = (origin - params.gridOrigin.xyz) / params.spacing.xyz;
    r.d = direction / params.spacing.xyz;
    return r;
}

dvec3 rayAt(GridRay r, double t) {
    precise dvec3 p = r.o + r.d * t;
    return p;
}

// Slab test; an axis with d_a == 0 never limits t, and the ray must then lie in 0 <= o_a < N_a. Written out per
// axis without a loop or an early return: llvmpipe neither unrolls a loop that returns nor skips the code after a
// return, and it runs every loop's body for all invocations of a SIMD batch.
void clipSlab(double o, double d, int n, inout double t0, inout double t1, inout bool outside) {
    precise double ta = (0.0LF - o) / d;
    precise double tb = (double(n) - o) / d;
    bool parallel = d == 0.0LF;
    outside = outside || (parallel && !(o >= 0.0LF && o < double(n)));
    t0 = parallel ? t0 : max(t0, min(ta, tb));
    t1 = parallel ? t1 : min(t1, max(ta, tb));
}

RayInterval intersectGrid(GridRay r) {
    double t0 = 0.0LF, t1 = kInfinity;
    bool outside = false;
    clipSlab(r.o.x, r.d.x, params.dims.x, t0, t1, outside);
    clipSlab(r.o.y, r.d.y, params.dims.y, t0, t1, outside);
    clipSlab(r.o.z, r.d.z, params.dims.z, t0, t1, outside);
    if (outside || !(t0 < t1)) return RayInterval(0.0LF, 0.0LF);
    return RayInterval(t0, t1);
}

bool intervalEmpty(RayInterval iv) { return !(iv.tEntry < iv.tExit); }

double latticeT(RayInterval iv, double k) {
    precise double t = iv.tEntry + k * params.dt;
    return t;
}

// Samples with t_k < tExit, exactly as the comparison decides.
double latticeCount(RayInterval iv) {
    if (intervalEmpty(iv)) return 0.0LF;
    precise double q = (iv.tExit - iv.tEntry) / params.dt;
    double k = max(1.0LF, ceil(q));
    while (k > 1.0LF && latticeT(iv, k - 1.0LF) >= iv.tExit) k -= 1.0LF;
    while (latticeT(iv, k) < iv.tExit) k += 1.0LF;
    return k;
}

ivec3 floorVoxel(dvec3 p) { return ivec3(floor(p)); }
ivec3 clampVoxel(ivec3 v) { return clamp(v, ivec3(0), params.dims.xyz - 1); }
ivec3 sampleVoxel(GridRay r, double t) { return clampVoxel(floorVoxel(rayAt(r, t))); }

int rayOctant(GridRay r) { return octantOf(r.d.x, r.d.y, r.d.z); }

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

double pcLeapSamples(int r, GridRay ray) {
    double speed = max(max(abs(ray.d.x), abs(ray.d.y)), abs(ray.d.z));
    precise double q = double(r) / (params.dt * speed);
    return max(1.0LF, 1.0LF + floor(q));
}

double boxExitT(GridRay ray, ivec3 v, int oct, ivec3 ext) {
    double t = kInfinity;
    for (int a = 0; a < 3; ++a) {
        if (ray.d[a] == 0.0LF) continue;
        int s = octantSign(oct, a);
        double far = double(v[a] + s * (ext[a] - 1) + (s > 0 ? 1 : 0));
        precise double ta = (far - ray.o[a]) / ray.d[a];
        t = min(t, ta);
    }
    return t;
}

double boxLeapSamples(double tBoxExit, double t) {
    precise double q = (tBoxExit - t) / params.dt;
    return max(1.0LF, ceil(q));
}

// Trilinear sampling: a leap whose box is the voxel alone may start in a border voxel, inside which the
// interpolated value changes; such a voxel is stepped sample by sample.
double trilinearLeapSamples(double wanted, VoxelBox box) { return box.lo == box.hi ? 1.0LF : wanted; }

// render/ray_setup.h's beforeFarFaces: whether the sample at t lies in the box that holds the span's first
// sample's voxel, as floorVoxel places it (only the far face of each axis can be crossed).
bool beforeFarFaces(GridRay ray, double t, VoxelBox box) {
    dvec3 p = rayAt(ray, t);
    bvec3 pastHi = greaterThanEqual(p, dvec3(box.hi + 1)), pastLo = lessThan(p, dvec3(box.lo));
    bvec3 climbing = greaterThan(ray.d, dvec3(0.0LF)), descending = lessThan(ray.d, dvec3(0.0LF));
    return !((climbing.x && pastHi.x) || (climbing.y && pastHi.y) || (climbing.z && pastHi.z) ||
             (descending.x && pastLo.x) || (descending.y && pastLo.y) || (descending.z && pastLo.z));
}

// The leap taken from sample k of kCount: never past the volume exit, never to a sample whose floor voxel
// rounding put outside the box. Always >= 1.
double leapCount(GridRay ray, RayInterval iv, double k, double kCount, double wanted, VoxelBox box) {
    double n = floor(min(wanted, kCount - k));
    while (n > 1.0LF && !beforeFarFaces(ray, latticeT(iv, k + n - 1.0LF), box)) n -= 1.0LF;
    return max(n, 1.0LF);
}

#endif
