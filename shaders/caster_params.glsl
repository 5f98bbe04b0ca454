// The render parameters, uploaded once per frame, and the per-dispatch push constants: their structs and
// bindings are device_contract.h's.
#ifndef VR_CASTER_PARAMS_GLSL
#define VR_CASTER_PARAMS_GLSL

#include "device_contract.h"

// A storage buffer, not a uniform block: lavapipe specializes a shader on up to four values of a uniform block that
// decide branches or are copied into variables used five times or more, and CasterParams holds the view. Each new
// view then compiled an LLVM variant of its own: 0.2-0.3 s of a one-view render whose Mesa cache had not seen that
// view. It reads the block once per invocation (copyUniforms), so the frame costs the same.
layout(set = 0, binding = kBindingParams, std140) readonly buffer Params { CasterParams P; };
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
