// The render parameters, uploaded once per frame (mirrored by CasterParams in volrender/vulkan/caster_params.h),
// and the per-tile push constants.
#ifndef VR_CASTER_PARAMS_GLSL
#define VR_CASTER_PARAMS_GLSL

layout(set = 0, binding = 0, std140) uniform Params {
    dvec4 eye;         // Camera::eye
    dvec4 forward;     // Camera basis
    dvec4 right;
    dvec4 up;
    dvec4 gridOrigin;  // GridGeometry::origin
    dvec4 spacing;     // GridGeometry::spacing
    double halfHeight; // Camera::halfHeight
    double dt;         // step in world units
    double ert;        // early ray termination threshold
    double ertDepth;   // the optical depth where opacity reaches ert (render/span.h terminationDepth)
    double loopProbe;  // 2: trip count of the loop that detects a driver's loop limit (caster.comp)
    ivec4 dims;        // voxels per axis
    ivec2 imageSize;   // width, height
    uint maxIterations;
    ivec4 octantSlot[2];  // ACD/EACD: z-slab of each octant in the field image, -1 when not uploaded
    vec4 light;        // xyz: unit direction toward the light; w = 1 when set, 0 for a headlight
    vec4 material;     // ambient, diffuse, specular, shininess
    vec4 background;   // rgb
} P;

// One dispatch renders one brick of one tile for the rays of one pass (volrender/vulkan/vulkan_renderer.cpp).
layout(push_constant) uniform Tile {
    ivec2 tileOrigin;  // first pixel of this dispatch
    ivec2 tileSize;    // pixels of this dispatch (the output buffers hold one tile)
    ivec4 brickLo;     // the brick's core (inclusive, global voxels): samples whose voxel lies in it are this
    ivec4 brickHi;     // dispatch's
    ivec4 imageLo;     // global voxel of texel (0, 0, 0) of the brick's images
    ivec4 imageDims;   // texels of one slab of the brick's images
    int firstDispatch; // 1: start every ray of the tile
    int lastDispatch;  // 1: a ray left unfinished was in no pass (a bug)
    int passAxes;      // this pass takes the rays whose octant bits on passAxes ...
    int passSigns;     // ... are passSigns (the bricks come in an order they all cross them in)
} T;

// Every member the casters read, copied once per invocation by copyUniforms() before anything else: llvmpipe
// (Mesa 22) reads a block member as a gather over the invocations of its SIMD batch, every time the shader reads
// it, once control flow may differ between them (after the early return of pixels outside the tile).
dvec3 uEye, uForward, uRight, uUp, uGridOrigin, uSpacing;
double uHalfHeight, uDt, uErt, uErtDepth, uLoopProbe;
ivec3 uDims, uBrickLo, uBrickHi, uImageLo;
ivec2 uImageSize, uTileOrigin, uTileSize;
int uSlabDepth;  // texels of one slab of the brick's images along z
int uFirstDispatch, uLastDispatch, uPassAxes, uPassSigns;
ivec4 uOctantSlot[2];
uint uMaxIterations;
vec4 uLight, uMaterial, uBackground;

void copyUniforms() {
    uEye = P.eye.xyz;
    uForward = P.forward.xyz;
    uRight = P.right.xyz;
    uUp = P.up.xyz;
    uGridOrigin = P.gridOrigin.xyz;
    uSpacing = P.spacing.xyz;
    uHalfHeight = P.halfHeight;
    uDt = P.dt;
    uErt = P.ert;
    uErtDepth = P.ertDepth;
    uLoopProbe = P.loopProbe;
    uDims = P.dims.xyz;
    uImageSize = P.imageSize;
    uMaxIterations = P.maxIterations;
    uOctantSlot = P.octantSlot;
    uLight = P.light;
    uMaterial = P.material;
    uBackground = P.background;
    uTileOrigin = T.tileOrigin;
    uTileSize = T.tileSize;
    uBrickLo = T.brickLo.xyz;
    uBrickHi = T.brickHi.xyz;
    uImageLo = T.imageLo.xyz;
    uSlabDepth = T.imageDims.z;
    uFirstDispatch = T.firstDispatch;
    uLastDispatch = T.lastDispatch;
    uPassAxes = T.passAxes;
    uPassSigns = T.passSigns;
}

#endif
