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
    double loopProbe;  // 2: trip count of the loop that detects a driver's loop limit (caster.comp)
    ivec4 dims;        // voxels per axis
    ivec2 imageSize;   // width, height
    int perspective;   // 1: perspective camera
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

// The members the casters' loop reads, copied once per invocation by copyUniforms(): llvmpipe (Mesa 22)
// reads a block member as a gather over the invocations of its SIMD batch, every time the shader reads it.
double uDt, uErt;
ivec3 uDims, uBrickLo, uBrickHi, uImageLo;
int uSlabDepth;  // texels of one slab of the brick's images along z
uint uMaxIterations;
vec4 uMaterial;

void copyUniforms() {
    uDt = P.dt;
    uErt = P.ert;
    uDims = P.dims.xyz;
    uBrickLo = T.brickLo.xyz;
    uBrickHi = T.brickHi.xyz;
    uImageLo = T.imageLo.xyz;
    uSlabDepth = T.imageDims.z;
    uMaxIterations = P.maxIterations;
    uMaterial = P.material;
}

#endif
