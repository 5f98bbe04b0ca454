// Host mirror of the caster's uniform block (shaders/caster_params.glsl, std140) and push constants.
#pragma once
#include <cstddef>
#include <cstdint>

namespace vr {

struct CasterParams {
    double eye[4], forward[4], right[4], up[4];
    double gridOrigin[4], spacing[4];
    double halfHeight, dt, ert, ertDepth, loopProbe;  // ertDepth: terminationDepth(ert); loopProbe: 2 (caster.comp)
    alignas(16) int32_t dims[4];  // std140: an ivec4 starts on 16 bytes
    int32_t imageSize[2];
    uint32_t maxIterations;
    int32_t padding;  // std140 starts the array below on 16 bytes
    int32_t octantSlot[8];
    float light[4];
    float material[4];
    float background[4];
};
static_assert(offsetof(CasterParams, halfHeight) == 192);
static_assert(offsetof(CasterParams, dims) == 240);
static_assert(offsetof(CasterParams, octantSlot) == 272);
static_assert(offsetof(CasterParams, light) == 304);
static_assert(sizeof(CasterParams) == 352);

// One dispatch: a tile, one brick, one pass (the Tile block of shaders/caster_params.glsl).
struct TilePush {
    int32_t origin[2];
    int32_t size[2];
    int32_t brickLo[4], brickHi[4];
    int32_t imageLo[4], imageDims[4];
    int32_t firstDispatch, lastDispatch;
    int32_t passAxes, passSigns;
};
static_assert(offsetof(TilePush, brickLo) == 16);
static_assert(offsetof(TilePush, firstDispatch) == 80);
static_assert(sizeof(TilePush) == 96);

}  // namespace vr
