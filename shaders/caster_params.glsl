// The render parameters, uploaded once per frame, and the per-dispatch push constants: their structs and
// bindings are device_contract.h's.
#ifndef VR_CASTER_PARAMS_GLSL
#define VR_CASTER_PARAMS_GLSL

#include "device_contract.h"

layout(set = 0, binding = kBindingParams, std140) uniform Params { CasterParams P; };
layout(push_constant) uniform Tile { TilePush T; };

// What the casters read, copied once per invocation by copyUniforms() before anything else: llvmpipe (Mesa 22)
// reads a block member as a gather over the invocations of its SIMD batch, every time the shader reads it, once
// control flow may differ between them (after the early return of pixels outside the tile). glslang copies a
// block into a private struct member by member.
CasterParams params;
TilePush tile;

void copyUniforms() {
    params = P;
    tile = T;
}

#endif
