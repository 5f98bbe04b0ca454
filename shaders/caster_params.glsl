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

layout(push_constant) uniform Tile {
    ivec2 tileOrigin;  // first pixel of this dispatch
    ivec2 tileSize;    // pixels of this dispatch (the output buffers hold one tile)
} T;

#endif
