// The four casters of docs/ALGORITHMS.md section 5 in one loop: renderCpu's trace in GLSL.
// Specialization constants pick the caster, the sampling and the shading, so each variant compiles to a
// pipeline without the others' branches. One invocation per pixel of one tile and one brick (brick_state.glsl:
// a ray's state carries over from brick to brick, so bricks change no leap). Each span is shaded once, at its
// first sample, as the CPU reference does (equal to shading every sample for a directional light or headlight
// when thresholds are 0).
#version 450
#extension GL_GOOGLE_include_directive : require

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
    float sigma;
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
    SampleValue s = SampleValue(c.a, c.rgb, vec3(0.0));
    if (SHADING) s.normal = imageLoad(normals, brickTexel(v)).xyz;
    return s;
}

// Cell-centred trilinear: voxel v's value sits at v + 0.5; clamped to the edge outside.
SampleValue trilinearSample(vec3 p) {
    precise vec3 q = p - vec3(0.5);
    ivec3 base = floorVoxel(q);
    precise vec3 f = q - vec3(base);
    SampleValue s = SampleValue(0.0, vec3(0.0), vec3(0.0));
    for (int c = 0; c < 8; ++c) {
        ivec3 bit = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        ivec3 u = clampVoxel(base + bit);
        vec3 w3 = mix(1.0 - f, f, bvec3(bit));
        precise float w = w3.x * w3.y * w3.z;
        vec4 cs = imageLoad(classified, brickTexel(u));
        s.sigma += w * cs.a;
        s.colour += cs.rgb * w;
        if (SHADING) s.normal += imageLoad(normals, brickTexel(u)).xyz * w;
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
    uvec2 inGroup = uvec2((l.x & 3u) | ((l.y & 1u) << 2), (l.y & ~1u) | (l.x >> 2));
    ivec2 local = ivec2(gl_WorkGroupID.xy * uint(kWorkgroupSize) + inGroup);
    if (any(greaterThanEqual(local, tile.tileSize))) return;
    ivec2 pixel = tile.tileOrigin + local;
    uint outIndex = uint(local.y * tile.tileSize.x + local.x);

    vec3 direction;
    GridRay g = cameraGridRay(float(pixel.x) + 0.5, float(pixel.y) + 0.5, direction);
    RayInterval iv = intersectGrid(g);
    uint kCount = latticeCount(iv);
    LeapSlack slack = leapSlack(g, iv);
    int oct = rayOctant(g);
    // Selected, not indexed: llvmpipe reads an array at a varying index lane by lane.
    ivec4 slots = oct < 4 ? params.octantSlot[0] : params.octantSlot[1];
    int slot = (oct & 1) == 0 ? ((oct & 2) == 0 ? slots.x : slots.z) : ((oct & 2) == 0 ? slots.y : slots.w);
    vec3 toEye = -direction;
    vec3 toLight = params.light.w != 0.0 ? params.light.xyz : toEye;

    bool missingOctant = (CASTER == kACD || CASTER == kEACD) && slot < 0 && kCount > 0u;
    bool firstDispatch = !BRICKED || tile.firstDispatch != 0, lastDispatch = !BRICKED || tile.lastDispatch != 0;
    RayState state = firstDispatch
                         ? RayState(vec4(vec3(0.0), 1.0), vec2(0.0), 0u, 0u, missingOctant ? kFailed : 0u)
                         : loadRayState(outIndex);
    vec3 colour = state.composite.rgb;
    float transmittance = state.composite.a;  // 1 - alpha, for the colour's weights
    vec2 depth = state.depth;                 // the optical depth: alpha and early ray termination
    uint iterations = state.iterations;
    bool failed = (state.flags & kFailed) != 0u;
    uint k = state.k;
    // This dispatch continues the ray when the ray is in this pass and its next sample lies in this brick; it
    // then runs until a sample leaves the brick (a leap may cross bricks: the next brick's pass finds it there).
    bool mine = k < kCount && (!BRICKED || (rayInPass(oct) && inBrick(sampleVoxel(g, iv, k))));
    if (!mine && !firstDispatch && !lastDispatch) return;
    for (uint n = 1u; mine && !failed && k < kCount && pairLess(depth, params.ertDepth); k += n) {
        ivec3 v = sampleVoxel(g, iv, k);
        if (BRICKED && !inBrick(v)) break;
        if (++iterations > params.maxIterations) {
            failed = true;
            break;
        }
        SampleValue s = TRILINEAR ? trilinearSample(samplePosition(g, iv, k)) : nearestSample(v);
        precise float sampleDepth = s.sigma * params.dt;

        // What the leap wants without and with the margin of docs/ALGORITHMS.md section 8.
        float wanted = 1.0, wantedWithMargin = 1.0;
        VoxelBox box = VoxelBox(v, v);
        if (CASTER == kPC) {
            int r = int(loadField(brickTexel(v)).r);
            wanted = pcLeapSamples(r, g, 0.0);
            wantedWithMargin = pcLeapSamples(r, g, slack.ball);
            box = chebyshevBall(v, r);
        } else if (CASTER == kACD || CASTER == kEACD) {
            uvec4 f = loadField(fieldTexel(v, slot));
            // A stored 0 would be a corrupt field; 1 (this voxel) is always true.
            ivec3 ext = CASTER == kACD ? max(ivec3(1), ivec3(f.r)) : decodeExtents(f);
            box = octantBox(v, oct, ext);
            vec3 exits = boxExitsT(g, v, oct, ext);
            float t = latticeT(iv, k);
            wanted = boxLeapSamples(exits, vec3(0.0), t);
            wantedWithMargin = boxLeapSamples(exits, slack.boxExit, t);
        }
        // The primitive caster steps one sample (n stays 1): it needs no termination count and no leap count.
        if (CASTER != kPrimitive) {
            float termination = samplesToTermination(depth, sampleDepth);
            if (TRILINEAR) wanted = trilinearLeapSamples(wanted, box);
            n = leapCount(g, iv, k, kCount, min(wanted, termination), min(wantedWithMargin, termination), box);
        }

        // The span's depth n sigma dt, exact as a pair: the same sum as n single samples'.
        vec2 spanDepth = CASTER == kPrimitive ? vec2(sampleDepth, 0.0) : exactProduct(float(n), sampleDepth);
        float spanAlpha = spanOpacity(spanDepth.x);
        if (spanAlpha > 0.0) {
            vec3 shaded = SHADING ? shade(s.colour, s.normal, toEye, toLight) : s.colour;
            precise float w = transmittance * spanAlpha;
            colour += shaded * w;
            transmittance -= w;
            depth = addPair(depth, spanDepth);
        }
    }

    // Some drivers end loops on their own: llvmpipe stops every loop of an invocation once 65535 iterations have run
    // in all of them, which would silently shorten a long ray. A loop whose trip count (2) the compiler cannot
    // know runs short afterwards exactly when that happened.
    int probe = 0;
    for (float i = 0.0; i < params.loopProbe; i += 1.0) ++probe;
    uint flags = state.flags | (probe < kLoopProbeTrips ? kCutShort : 0u);
    if (lastDispatch && k < kCount && pairLess(depth, params.ertDepth)) failed = true;  // in no pass: a bug
    if (failed) flags |= kFailed;
    // The next brick's dispatch reads this state; after the last one, nothing does.
    if (!lastDispatch) storeRayState(outIndex, RayState(vec4(colour, transmittance), depth, k, iterations, flags));

    // Alpha from the optical depth: exact to float rounding where 1 - transmittance would cancel.
    float alpha = spanOpacity(depth.x + depth.y);
    vec3 pixelColour = colour + params.background.rgb * (1.0 - alpha);
    outPixel[outIndex].colour = floatBitsToUint(vec4(pixelColour, alpha));
    outPixel[outIndex].counts = uvec4(k, iterations | flags, 0u, 0u);
}
