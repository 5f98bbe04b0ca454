// Bricks: a volume too large for one image is rendered one brick per dispatch, in an order every ray of the pass
// crosses them in; each ray's state (the lattice index it reached, the composite so far, its counters) is
// carried from one dispatch to the next, so that a split render takes the same leaps as an unsplit one.
#ifndef VR_BRICK_STATE_GLSL
#define VR_BRICK_STATE_GLSL

#include "caster_params.glsl"

layout(set = 0, binding = kBindingRayStates, std430) buffer RayStates { RayState rayState[]; };

// Member by member: glslang stores a whole struct into a buffer with an OpStore of mismatched types. Only a stereo
// left eye's variant loads and stores its bands' members (llvmpipe would move them lane by lane).
RayState loadRayState(uint i) {
    RayState s = RayState(rayState[i].composite, rayState[i].depth, rayState[i].k, rayState[i].iterations,
                          rayState[i].flags, 0.0, 0u, 0.0, vec4(0.0), 0u);
    if (STEREO_BANDS) {
        s.moment = rayState[i].moment;
        s.bandGathered = rayState[i].bandGathered;
        s.bandStartMoment = rayState[i].bandStartMoment;
        s.bandStart = rayState[i].bandStart;
        s.bandMask = rayState[i].bandMask;
    }
    return s;
}

void storeRayState(uint i, RayState s) {
    rayState[i].composite = s.composite;
    rayState[i].depth = s.depth;
    rayState[i].k = s.k;
    rayState[i].iterations = s.iterations;
    rayState[i].flags = s.flags;
    if (STEREO_BANDS) {
        rayState[i].moment = s.moment;
        rayState[i].bandGathered = s.bandGathered;
        rayState[i].bandStartMoment = s.bandStartMoment;
        rayState[i].bandStart = s.bandStart;
        rayState[i].bandMask = s.bandMask;
    }
}

bool inBrick(ivec3 v) { return all(greaterThanEqual(v, tile.brickLo.xyz)) && all(lessThanEqual(v, tile.brickHi.xyz)); }

bool rayInPass(int oct) { return (oct & tile.passAxes) == tile.passSigns; }

// Texel of a global voxel in this brick's scalar image.
ivec3 brickTexel(ivec3 v) { return v - tile.imageLo.xyz; }

// Texel of a global voxel in slab `slot` of this brick's field image (ACD / EACD stack octants along z).
ivec3 fieldTexel(ivec3 v, int slot) {
    ivec3 t = brickTexel(v);
    return ivec3(t.xy, slot * tile.imageDims.z + t.z);
}

// Texel of the hier field's block of 2^shift voxels that holds global voxel v, in slab `slot` of this brick's image
// of the blocks its images' voxels touch (volrender/vulkan/gpu_volume.cpp: brickBlocks), octants stacked along z.
ivec3 blockTexel(ivec3 v, int slot, int shift) {
    ivec3 lo = tile.imageLo.xyz >> shift;
    int depth = ((tile.imageLo.z + tile.imageDims.z - 1) >> shift) - lo.z + 1;
    ivec3 t = (v >> shift) - lo;
    return ivec3(t.xy, slot * depth + t.z);
}

#endif
