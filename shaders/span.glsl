// Span integration and shading on the casters' parameters: shaders/ray_math.h's math, with the optical depth as a
// float pair (numerics.glsl), so that early ray termination decides as the primitive caster does whatever the spans.
#ifndef VR_SPAN_GLSL
#define VR_SPAN_GLSL

#include "caster_params.glsl"
#include "numerics.glsl"
#include "ray_math.h"

// The samples until primitive stepping would reach ert: the pair's difference rounds to a float, and the lowering
// by 2^-20 relative is more than that rounding.
float samplesToTermination(vec2 depth, float sampleDepth) {
    return samplesToTermination(pairDifference(params.ertDepth, depth), sampleDepth, 1.0 / 1048576.0);
}

// The material is the parameters' (ambient, diffuse, specular, shininess).
vec3 shade(vec3 colour, vec3 normal, vec3 toEye, vec3 toLight) {
    return shade(colour, normal, toEye, toLight, params.material.x, params.material.y, params.material.z,
                 params.material.w);
}

#endif
