// Span integration and shading: render/span.h in GLSL, in float. The optical depth is a float pair
// (numerics.glsl), so that early ray termination decides as the primitive caster does whatever the spans.
#ifndef VR_SPAN_GLSL
#define VR_SPAN_GLSL

#include "caster_params.glsl"
#include "numerics.glsl"

// 1 - exp(-depth) without cancellation for a tiny optical depth; exactly 1 for an opaque span.
float spanOpacity(float depth) { return -vrExpm1(-depth); }

// Samples until primitive stepping would reach ert inside a span whose samples add sampleDepth = sigma dt each
// (+inf: never): the first m with depth + m sampleDepth >= ertDepth. The quotient is lowered by 2^-20 relative,
// more than its rounding, so the count is never above that m; one below it costs one more iteration. The
// division runs for sigma = 0 too and its result is not picked: llvmpipe runs both sides of a branch.
float samplesToTermination(vec2 depth, float sampleDepth) {
    precise float q = pairDifference(params.ertDepth, depth) / sampleDepth * (1.0 - 1.0 / 1048576.0);
    return sampleDepth <= 0.0 ? kInfinity : max(1.0, ceil(q));
}

// Two-sided Phong with one directional light; a flat voxel (zero normal) gets ambient + diffuse with the view
// vector as normal and no highlight.
vec3 shade(vec3 colour, vec3 normal, vec3 toEye, vec3 toLight) {
    bool isFlat = dot(normal, normal) == 0.0;
    vec3 n = isFlat ? toEye : normal;
    if (dot(n, toEye) < 0.0) n = -n;
    float nl = dot(n, toLight);
    float diffuse = abs(nl);
    float highlight = 0.0;
    if (!isFlat && nl > 0.0) {
        vec3 reflected = n * (2.0 * nl) - toLight;
        highlight = pow(max(0.0, dot(reflected, toEye)), params.material.w);
    }
    return colour * (params.material.x + params.material.y * diffuse) + vec3(params.material.z * highlight);
}

#endif
