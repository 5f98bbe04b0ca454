// Evaluates vrExpm1 over a buffer of arguments so the host can compare it with the C library's double expm1.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "numerics.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer Args { float x[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Expm1 { float expm1Out[]; };
layout(push_constant) uniform Count { uint count; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    expm1Out[i] = vrExpm1(x[i]);
}
