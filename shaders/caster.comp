// The four casters of docs/ALGORITHMS.md section 5 in one loop: renderCpu's trace in GLSL.
// Specialization constants pick the caster, the sampling and the shading, so each variant compiles to a
// pipeline without the others' branches. One invocation per pixel of one tile and one brick (brick_state.glsl:
// a ray's state carries over from brick to brick, so bricks change no leap). Each span is shaded once, at its
// first sample, as the CPU reference does (equal to shading every sample for a directional light or headlight
// when thresholds are 0).
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_gpu_shader_int64 : require

#include "device_contract.h"

layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize) in;

layout(constant_id = kSpecIdCaster) const int CASTER = kPrimitive;
layout(constant_id = kSpecIdTrilinear) const bool TRILINEAR = false;
layout(constant_id = kSpecIdShading) const bool SHADING = true;
// false: the volume is one brick, rendered in one dispatch per tile, so no ray state is carried (llvmpipe would
// run the state's loads and stores, lane by lane, even where a uniform condition turns them off).
layout(constant_id = kSpecIdBricked) const bool BRICKED = true;
// The camera's projection: llvmpipe would compute both cameras' rays for every pixel.
layout(constant_id = kSpecIdPerspective) const bool PERSPECTIVE = false;

#include "caster_params.glsl"
#include "ray_setup.glsl"
#include "span.glsl"
#include "brick_state.glsl"
#include "extent_code.glsl"

// Storage images (volrender/vulkan/gpu_buffer.h): llvmpipe loads them more cheaply than texelFetch.
layout(set = 0, binding = kBindingClassified, rgba32f) uniform readonly image3D classified;
layout(set = 0, binding = kBindingNormals, rgba16_snorm) uniform readonly image3D normals;
// The field, bound by its format: PC (r), ACD (r per octant slab) and joint8 EACD in R8, log16 EACD in R16, exact
// EACD in RGBA8 (rgb); the other two are unused.
layout(set = 0, binding = kBindingField8, r8ui) uniform readonly uimage3D field8;
layout(set = 0, binding = kBindingField16, r16ui) uniform readonly uimage3D field16;
layout(set = 0, binding = kBindingFieldRGBA8, rgba8ui) uniform readonly uimage3D fieldRGBA8;
layout(set = 0, binding = kBindingOutPixels, std430) writeonly buffer OutPixels { OutPixel outPixel[]; };

struct SampleValue {
    double sigma;  // double as the CPU reference's, so that opacity sums agree to rounding
    vec3 colour;
    vec3 normal;
};

uvec4 loadField(ivec3 texel) {
    if (CASTER == kEACD && EACD_CODE == kLog16) return imageLoad(field16, texel);
    if (CASTER == kEACD && EACD_CODE == kExact) return imageLoad(fieldRGBA8, texel);
    return imageLoad(field8, texel);
}

SampleValue nearestSample(ivec3 v) {
    vec4 c = imageLoad(classified, brickTexel(v));
    SampleValue s = SampleValue(double(c.a), c.rgb, vec3(0.0));
    if (SHADING) s.normal = imageLoad(normals, brickTexel(v)).xyz;
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
        vec4 cs = imageLoad(classified, brickTexel(u));
        s.sigma += w * double(cs.a);
        s.colour += cs.rgb * float(w);
        if (SHADING) s.normal += imageLoad(normals, brickTexel(u)).xyz * float(w);
    }
    float len = length(s.normal);
    s.normal = len > float(kFlatNormalLength) ? s.normal / len : vec3(0.0);
    return s;
}

void main() {
    copyUniforms();
    // llvmpipe runs the 8 invocations of a row of this 8x8 workgroup as one SIMD batch, for as long as its
    // slowest ray takes: each batch takes a 4x2 block of pixels, whose rays stay closer together than an 8x1 row's.
    uvec2 l = gl_LocalInvocationID.xy;
    uvec2 inGroup = uvec2((l.x & 3u) | ((l.y & 1u) << 2), (l.y & ~1u) | (l.x >> 2));
    ivec2 local = ivec2(gl_WorkGroupID.xy * uint(kWorkgroupSize) + inGroup);
    if (any(greaterThanEqual(local, tile.tileSize))) return;
    ivec2 pixel = tile.tileOrigin + local;
    uint outIndex = uint(local.y * tile.tileSize.x + local.x);

    dvec3 direction;
    GridRay g = cameraGridRay(double(pixel.x) + 0.5LF, double(pixel.y) + 0.5LF, direction);
    RayInterval iv = intersectGrid(g);
    double kCount = latticeCount(iv);
    int oct = rayOctant(g);
    // Selected, not indexed: llvmpipe reads an array at a varying index lane by lane.
    ivec4 slots = oct < 4 ? params.octantSlot[0] : params.octantSlot[1];
    int slot = (oct & 1) == 0 ? ((oct & 2) == 0 ? slots.x : slots.z) : ((oct & 2) == 0 ? slots.y : slots.w);
    vec3 toEye = -vec3(direction);
    vec3 toLight = params.light.w != 0.0 ? params.light.xyz : toEye;

    bool missingOctant = (CASTER == kACD || CASTER == kEACD) && slot < 0 && kCount > 0.0LF;
    bool firstDispatch = !BRICKED || tile.firstDispatch != 0, lastDispatch = !BRICKED || tile.lastDispatch != 0;
    RayState state = firstDispatch
                         ? RayState(dvec4(0.0LF), 0.0LF, 0.0LF, 0u, missingOctant ? kFailed : 0u)
                         : loadRayState(outIndex);
    dvec3 colour = state.composite.rgb;
    double alpha = state.composite.a;
    precise double depth = state.depth;
    uint iterations = state.iterations;
    bool failed = (state.flags & kFailed) != 0u;
    double k = state.k;
    // This dispatch continues the ray when the ray is in this pass and its next sample lies in this brick; it
    // then runs until a sample leaves the brick (a leap may cross bricks: the next brick's pass finds it there).
    bool mine = k < kCount && (!BRICKED || (rayInPass(oct) && inBrick(sampleVoxel(g, latticeT(iv, k)))));
    if (!mine && !firstDispatch && !lastDispatch) return;
    for (double n = 1.0LF; mine && !failed && k < kCount && alpha < params.ert; k += n) {
        double t = latticeT(iv, k);
        ivec3 v = sampleVoxel(g, t);
        if (BRICKED && !inBrick(v)) break;
        if (++iterations > params.maxIterations) {
            failed = true;
            break;
        }
        SampleValue s = TRILINEAR ? trilinearSample(rayAt(g, t)) : nearestSample(v);

        double wanted = 1.0LF;
        VoxelBox box = VoxelBox(v, v);
        if (CASTER == kPC) {
            int r = int(loadField(brickTexel(v)).r);
            wanted = pcLeapSamples(r, g);
            box = chebyshevBall(v, r);
        } else if (CASTER == kACD || CASTER == kEACD) {
            uvec4 f = loadField(fieldTexel(v, slot));
            // A stored 0 would be a corrupt field; 1 (this voxel) is always true.
            ivec3 ext = CASTER == kACD ? max(ivec3(1), ivec3(f.r)) : decodeExtents(f);
            box = octantBox(v, oct, ext);
            wanted = boxLeapSamples(boxExitT(g, v, oct, ext), t);
        }
        // The primitive caster steps one sample (n stays 1): it needs no termination count and no leap check.
        if (CASTER != kPrimitive) {
            if (TRILINEAR) wanted = trilinearLeapSamples(wanted, box);
            wanted = min(wanted, samplesToTermination(depth, s.sigma));
            n = leapCount(g, iv, k, kCount, wanted, box);
        }

        precise double length = n * params.dt;
        double spanAlpha = spanOpacity(s.sigma, length);
        if (spanAlpha > 0.0LF) {
            vec3 shaded = SHADING ? shade(s.colour, s.normal, toEye, toLight) : s.colour;
            precise double w = (1.0LF - alpha) * spanAlpha;
            colour += dvec3(shaded) * w;
            alpha += w;
            if (CASTER != kPrimitive) depth += s.sigma * length;  // for the termination count only
        }
    }

    // Some drivers end loops on their own: llvmpipe stops every loop of an invocation once 65535 iterations have run
    // in all of them, which would silently shorten a long ray. A loop whose trip count (2) the compiler cannot
    // know runs short afterwards exactly when that happened.
    int probe = 0;
    for (double i = 0.0LF; i < params.loopProbe; i += 1.0LF) ++probe;
    uint flags = state.flags | (probe < kLoopProbeTrips ? kCutShort : 0u);
    if (lastDispatch && k < kCount && alpha < params.ert) failed = true;  // in no pass: a bug
    if (failed) flags |= kFailed;
    // The next brick's dispatch reads this state; after the last one, nothing does.
    if (!lastDispatch) storeRayState(outIndex, RayState(dvec4(colour, alpha), k, depth, iterations, flags));

    uvec4 rgba = floatBitsToUint(vec4(vec3(colour + dvec3(params.background.rgb) * (1.0LF - alpha)), float(alpha)));
    outPixel[outIndex].words = u64vec4(packUint2x32(rgba.xy), packUint2x32(rgba.zw), uint64_t(k), iterations | flags);
}
