// The four casters of ALGORITHMS.md section 5 in one loop: the GLSL mirror of renderCpu's trace (keep in step).
// Specialization constants pick the caster, the sampling and the shading, so each variant compiles to a
// pipeline without the others' branches. One invocation per pixel of one tile and one brick (brick_state.glsl:
// a ray's state carries over from brick to brick, so bricks change no leap). Each span is shaded once, at its
// first sample, as the CPU reference does (equal to shading every sample for a directional light or headlight
// when thresholds are 0).
#version 450
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const int CASTER = 0;  // 0 primitive, 1 PC, 2 ACD, 3 EACD
layout(constant_id = 1) const bool TRILINEAR = false;
layout(constant_id = 2) const bool SHADING = true;
const int kPrimitive = 0, kPC = 1, kACD = 2, kEACD = 3;

#include "caster_params.glsl"
#include "ray_setup.glsl"
#include "span.glsl"
#include "brick_state.glsl"
#include "extent_code.glsl"

layout(set = 0, binding = 1) uniform sampler3D classified;  // rgb colour, a: extinction sigma
layout(set = 0, binding = 2) uniform sampler3D normals;     // xyz: unit normal or 0 (flat); shading only
layout(set = 0, binding = 3) uniform usampler3D field;      // PC: r; ACD: r per octant slab; EACD: rgb, or r coded
layout(set = 0, binding = 4, std430) writeonly buffer OutColour { vec4 outColour[]; };
layout(set = 0, binding = 5, std430) writeonly buffer OutIterations { uint outIterations[]; };
layout(set = 0, binding = 6, std430) writeonly buffer OutSamples { uvec2 outSamples[]; };

// Set in an iteration count: the ray hit the cap, needed an octant that was not uploaded or was in no pass over
// the bricks (a bug); the driver ended the loops early.
const uint kFailed = 0x80000000u, kCutShort = 0x40000000u;
// Shorter interpolated normals than this count as flat (as the CPU reference).
const float kFlatNormalLength = 1e-6;

struct SampleValue {
    double sigma;  // double as the CPU reference's, so that opacity sums agree to rounding
    vec3 colour;
    vec3 normal;
};

SampleValue nearestSample(ivec3 v) {
    vec4 c = texelFetch(classified, brickTexel(v), 0);
    SampleValue s = SampleValue(double(c.a), c.rgb, vec3(0.0));
    if (SHADING) s.normal = texelFetch(normals, brickTexel(v), 0).xyz;
    return s;
}

// Cell-centred trilinear: voxel v's value sits at v + 0.5; clamped to the edge outside.
SampleValue trilinearSample(dvec3 p) {
    precise dvec3 q = p - dvec3(0.5LF);
    ivec3 base = floorVoxel(q);
    precise dvec3 f = q - dvec3(base);
    SampleValue s = SampleValue(0.0LF, vec3(0.0), vec3(0.0));
    for (int c = 0; c < 8; ++c) {
        ivec3 bit = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        ivec3 u = clampVoxel(base + bit);
        dvec3 w3 = mix(1.0LF - f, f, bvec3(bit));
        precise double w = w3.x * w3.y * w3.z;
        vec4 cs = texelFetch(classified, brickTexel(u), 0);
        s.sigma += w * double(cs.a);
        s.colour += cs.rgb * float(w);
        if (SHADING) s.normal += texelFetch(normals, brickTexel(u), 0).xyz * float(w);
    }
    float len = length(s.normal);
    s.normal = len > kFlatNormalLength ? s.normal / len : vec3(0.0);
    return s;
}

void main() {
    copyUniforms();
    // llvmpipe runs the 8 invocations of a row of this 8x8 workgroup as one SIMD batch, for as long as its
    // slowest ray takes: each batch takes a 4x2 block of pixels, whose rays stay closer together than an 8x1 row's.
    uvec2 l = gl_LocalInvocationID.xy;
    ivec2 local = ivec2(gl_WorkGroupID.xy * 8u + uvec2((l.x & 3u) | ((l.y & 1u) << 2), (l.y & ~1u) | (l.x >> 2)));
    if (any(greaterThanEqual(local, T.tileSize))) return;
    ivec2 pixel = T.tileOrigin + local;
    uint outIndex = uint(local.y * T.tileSize.x + local.x);

    dvec3 direction;
    GridRay g = cameraGridRay(double(pixel.x) + 0.5LF, double(pixel.y) + 0.5LF, direction);
    RayInterval iv = intersectGrid(g);
    double kCount = latticeCount(iv);
    int oct = rayOctant(g);
    int slot = P.octantSlot[oct >> 2][oct & 3];
    vec3 toEye = -vec3(direction);
    vec3 toLight = P.light.w != 0.0 ? P.light.xyz : toEye;

    bool missingOctant = (CASTER == kACD || CASTER == kEACD) && slot < 0 && kCount > 0.0LF;
    RayState state = T.firstDispatch != 0
                         ? RayState(dvec4(0.0LF), 0.0LF, 0.0LF, 0u, missingOctant ? kFailed : 0u)
                         : loadRayState(outIndex);
    dvec3 colour = state.composite.rgb;
    double alpha = state.composite.a;
    uint iterations = state.iterations;
    double samples = state.samples;
    bool failed = (state.flags & kFailed) != 0u;
    double k = state.k;
    // This dispatch continues the ray when the ray is in this pass and its next sample lies in this brick; it
    // then runs until a sample leaves the brick (a leap may cross bricks: the next brick's pass finds it there).
    bool mine = rayInPass(oct) && k < kCount && inBrick(sampleVoxel(g, latticeT(iv, k)));
    if (!mine && T.firstDispatch == 0 && T.lastDispatch == 0) return;
    for (double n = 1.0LF; mine && !failed && k < kCount && alpha < uErt; k += n) {
        double t = latticeT(iv, k);
        ivec3 v = sampleVoxel(g, t);
        if (!inBrick(v)) break;
        if (++iterations > uMaxIterations) {
            failed = true;
            break;
        }
        SampleValue s = TRILINEAR ? trilinearSample(rayAt(g, t)) : nearestSample(v);

        double wanted = 1.0LF;
        VoxelBox box = VoxelBox(v, v);
        if (CASTER == kPC) {
            int r = int(texelFetch(field, brickTexel(v), 0).r);
            wanted = pcLeapSamples(r, g);
            box = chebyshevBall(v, r);
        } else if (CASTER == kACD || CASTER == kEACD) {
            uvec4 f = texelFetch(field, fieldTexel(v, slot), 0);
            // A stored 0 would be a corrupt field; 1 (this voxel) is always true.
            ivec3 ext = CASTER == kACD ? max(ivec3(1), ivec3(f.r)) : decodeExtents(f);
            box = octantBox(v, oct, ext);
            wanted = boxLeapSamples(boxExitT(g, v, oct, ext), t);
        }
        if (TRILINEAR) wanted = trilinearLeapSamples(wanted, box);
        wanted = min(wanted, samplesToTermination(alpha, s.sigma));
        n = leapCount(g, iv, k, kCount, wanted, box);

        double spanAlpha = spanOpacity(s.sigma, n * uDt);
        if (spanAlpha > 0.0LF) {
            vec3 shaded = SHADING ? shade(s.colour, s.normal, toEye, toLight) : s.colour;
            precise double w = (1.0LF - alpha) * spanAlpha;
            colour += dvec3(shaded) * w;
            alpha += w;
        }
        samples += n;
    }

    // Some drivers end loops on their own: llvmpipe stops every loop of an invocation once 65535 iterations have run
    // in all of them, which would silently shorten a long ray. A loop whose trip count (2) the compiler cannot
    // know runs short afterwards exactly when that happened.
    int probe = 0;
    for (double i = 0.0LF; i < P.loopProbe; i += 1.0LF) ++probe;
    uint flags = state.flags | (probe < 2 ? kCutShort : 0u);
    if (T.lastDispatch != 0 && k < kCount && alpha < uErt) failed = true;  // in no pass: a bug
    if (failed) flags |= kFailed;
    // The next brick's dispatch reads this state; after the last one, nothing does.
    if (T.lastDispatch == 0) storeRayState(outIndex, RayState(dvec4(colour, alpha), k, samples, iterations, flags));

    outColour[outIndex] = vec4(vec3(colour + dvec3(P.background.rgb) * (1.0LF - alpha)), float(alpha));
    outIterations[outIndex] = iterations | flags;
    double high = floor(samples / 4294967296.0LF);
    outSamples[outIndex] = uvec2(uint(samples - high * 4294967296.0LF), uint(high));
}
