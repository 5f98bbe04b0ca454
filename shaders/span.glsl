// Span integration and shading: render/span.h in GLSL. Opacity is integrated in double (see numerics.glsl), the
// shade in float.
#ifndef VR_SPAN_GLSL
#define VR_SPAN_GLSL

#include "caster_params.glsl"
#include "numerics.glsl"

// 1 - exp(-sigma L) without cancellation for tiny sigma L; exactly 1 for an opaque span.
double spanOpacity(double sigma, double len) { return -vrExpm1(-sigma * len); }

// Samples until primitive stepping would reach ert inside a span of extinction sigma, from the optical depth
// (+inf: never). The division runs for sigma = 0 too and its result is not picked: llvmpipe runs both sides of a
// branch.
double samplesToTermination(double depth, double sigma) {
    precise double q = (params.ertDepth - depth) / (sigma * params.dt) * kTerminationSlack;
    return sigma <= 0.0LF ? kInfinity : max(1.0LF, ceil(q));
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
