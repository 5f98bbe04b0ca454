// What the host (volrender/vulkan) and the casters (shaders/caster.comp) agree on, stated once: the C++ compiler
// and glslang both read this file. It holds the descriptor bindings, the specialization-constant ids and values,
// the flags and constants both sides use, and the structs of the uniform block, the push constants and the
// per-pixel buffers, written in GLSL types (C++ takes them from glsl_layout_types.h, aligned as std140 / std430
// align them; the static_asserts at the end pin the offsets). The shaders declare the blocks around these structs.
#ifndef VR_DEVICE_CONTRACT_H
#define VR_DEVICE_CONTRACT_H

#include "shared_language.h"

#ifdef __cplusplus
#include <cstddef>

#include "glsl_layout_types.h"
namespace vr::device {
#endif

// Descriptor set 0.
VR_CONSTANT int kBindingParams = 0;         // storage buffer: CasterParams (caster_params.glsl says why)
VR_CONSTANT int kBindingOutColours = 1;     // storage buffer: OutPixel::colour per pixel of the tile
VR_CONSTANT int kBindingRayStates = 2;      // storage buffer: RayState per pixel of the tile
VR_CONSTANT int kBindingExtentTable = 3;    // uniform: uvec4 per entry of extentDecodeTable() (core/extent_code.h)
VR_CONSTANT int kExtentTableEntries = 256;
VR_CONSTANT int kBindingTransferTable = 4;  // storage texel buffer, RGBA32F: a texel per entry of the transfer
                                            // table (rgb colour, a: extinction sigma; core/scalar_classification.h)
// Storage images of the scalars in the volume's own type: integer scalars packed along x into 32-bit words
// (scalarWordShift), float32 scalars one a texel; the scalar type's specialization constant picks the one the casters
// read.
VR_CONSTANT int kBindingScalarWords = 5;    // R32_UINT: 4 uint8, 2 uint16 or 2 int16 scalars a texel
VR_CONSTANT int kBindingScalarsFloat = 6;   // R32_SFLOAT
VR_CONSTANT int kBindingField8 = 7;         // storage images of the distance field, one per format: R8 (PC, ACD,
VR_CONSTANT int kBindingField16 = 8;        // joint8 EACD), R16 (log16 EACD), RGBA8 (exact EACD)
VR_CONSTANT int kBindingFieldRGBA8 = 9;
VR_CONSTANT int kBindingBlockExtrema = 10;  // storage image RG32F: each block's scalar range (lo, hi) for the
                                            // blocks caster (render/block_extrema.h)
// A label map's labels packed as the integer scalars (R32_UINT: 4 uint8 or 2 uint16 labels a texel), and its table:
// an RGBA32F texel per label (rgb colour, a: extinction sigma; core/label_map.h).
VR_CONSTANT int kBindingLabelWords = 11;
VR_CONSTANT int kBindingLabelTable = 12;    // storage texel buffer, as the transfer table
VR_CONSTANT int kBindingPixelList = 13;     // storage buffer: uint count, then the rays to cast (ListRay), read
                                            // by the list variant (stereo re-casts: stereo_reprojection.h)
VR_CONSTANT int kBindingGradients = 14;     // R32_UINT: each voxel's stored gradient (gradient_code.h)
VR_CONSTANT int kBindingStereoBands = 15;   // storage buffer: a stereo left eye's segment of each band of each
                                            // pixel (uvec4), written by the bands variant (stereo_reprojection.h
                                            // bandTexel, packBandSegment)
VR_CONSTANT int kBindingOutCounts = 16;     // storage buffer: OutPixel::counts per pixel of the tile, written
                                            // where CasterParams::rayCounts is 1

// Specialization constants: each variant compiles to a pipeline without the others' branches.
VR_CONSTANT int kSpecIdTrilinear = 1;    // bool
VR_CONSTANT int kSpecIdShading = 2;      // bool
VR_CONSTANT int kSpecIdExtentCode = 3;   // one of the extent codes below
VR_CONSTANT int kSpecIdBricked = 4;      // bool: false for a volume of one brick (no ray state is carried)
VR_CONSTANT int kSpecIdPerspective = 5;  // bool: the camera's projection
VR_CONSTANT int kSpecIdScalarType = 6;   // one of the scalar types below: which scalar image the casters read
VR_CONSTANT int kSpecIdLabels = 8;       // one of the label types below: which label image the casters read
VR_CONSTANT int kSpecIdPixelList = 9;    // bool: cast the pixels of the list (kBindingPixelList), not a tile's
VR_CONSTANT int kSpecIdStoredGradients = 10;  // bool: shade by the stored gradients (kBindingGradients)
VR_CONSTANT int kSpecIdStereoBands = 11;      // bool: composite, the left eye of a stereo pair: record the bands
VR_CONSTANT int kSpecIdMarginLeaps = 12;      // bool: leaps take the samples their margin proves, unchecked
VR_CONSTANT int kSpecIdPieces = 13;           // the workgroup's third size: the pieces each composite ray is cast in
VR_CONSTANT int kMostPieces = 8;              // at most (a workgroup of 8 x 8 x 8 invocations)
VR_CONSTANT int kSpecIdPiecewise = 14;        // bool: the rays are cast in pieces (kSpecIdPieces above 1)
// The casters and the blends below are fixed per module instead (caster.comp's VR_CASTER and VR_BLEND).
VR_CONSTANT int kPrimitive = 0, kPC = 1, kACD = 2, kEACD = 3, kBlocks = 4, kHier = 5;
// The hierarchical EACD's block codes (core/distance_fields.h BlockEACD): log16 extents in blocks, this bit set where
// the block is homogeneous (0: a mixed block, stepped sample by sample).
VR_CONSTANT uint kHomogeneousBlock = 0x8000u;
// What a ray makes of its samples (render/render_settings.h Blend, in its order; shaders/blend.h).
VR_CONSTANT int kBlendComposite = 0, kBlendMIP = 1, kBlendMinIP = 2, kBlendAverage = 3, kBlendIso = 4;
VR_CONSTANT int kExact = 0, kLog16 = 1, kJoint8 = 2;  // how EACD extents are stored (core/extent_code.h)
// The scalars' type (core/volume.h ScalarType, in its order).
VR_CONSTANT int kScalarUInt8 = 0, kScalarInt16 = 1, kScalarUInt16 = 2, kScalarFloat32 = 3;
// The label map's type: none, or its labels in 8 or 16 bits.
VR_CONSTANT int kNoLabels = 0, kLabelsUInt8 = 1, kLabelsUInt16 = 2;
// How many integers of `bits` bits a 32-bit word packs along x, as a shift: 4 of 8 bits, 2 of 16, 1 of 32.
// llvmpipe loads a 32-bit texel faster than an 8- or 16-bit one: on lavapipe a frame with the scalars in words takes
// 22-25 % less time than with R8 or R16 texels, in the same bytes (docs/BENCH.md).
VR_FUNCTION int wordShift(int bits) { return bits == 8 ? 2 : bits == 16 ? 1 : 0; }
VR_FUNCTION int scalarBits(int scalarType) {
    return scalarType == kScalarUInt8 ? 8 : scalarType == kScalarFloat32 ? 32 : 16;
}

// The most clipping planes a render takes (RenderSettings::clipPlanes, CasterParams::clipPlanes).
VR_CONSTANT int kMaxClipPlanes = 6;

// One workgroup takes kWorkgroupSize x kWorkgroupSize pixels (caster.comp orders 8 x 8 of them in 4 x 2 blocks).
VR_CONSTANT int kWorkgroupSize = 8;

// Set in a pixel's iteration count: the ray hit the iteration cap, needed an octant that was not uploaded or was
// in no pass over the bricks (a bug); the driver ended the shader's loops early.
VR_CONSTANT uint kFailed = 0x80000000u, kCutShort = 0x40000000u;
// A ray that failed (kFailed or kCutShort) says so in its colour too, where a render without ray counts looks:
// its alpha's bits are a quiet NaN whose low bits hold those flags, shifted down by 28. A colour is never NaN
// otherwise (the loaders refuse NaN scalars).
VR_CONSTANT uint kFailureNaN = 0x7fc00000u;
VR_FUNCTION uint failureAlphaBits(uint flags) { return kFailureNaN | ((flags & (kFailed | kCutShort)) >> 28); }
VR_FUNCTION uint failureFlagsOf(uint alphaBits) {
    return (alphaBits & ~0xcu) == kFailureNaN ? (alphaBits & 0xcu) << 28 : 0u;
}
// Carried in a ray's state between bricks, never output: the iso-surface's side of the last sample, and a hit.
VR_CONSTANT uint kIsoInside = 0x20000000u, kIsoHit = 0x10000000u;
// The trip count of the loop that detects a driver's loop limit: uploaded (CasterParams::loopProbe), so the
// compiler cannot know it, and compared with what the loop counted.
VR_CONSTANT int kLoopProbeTrips = 2;

// Octant of a direction: bit a set when component a is negative (a zero counts as positive).
VR_FUNCTION int octantOf(VR_REAL dx, VR_REAL dy, VR_REAL dz) {
    return (dx < VR_REAL(0) ? 1 : 0) | (dy < VR_REAL(0) ? 2 : 0) | (dz < VR_REAL(0) ? 4 : 0);
}
// Step sign of axis a in octant oct.
VR_FUNCTION int octantSign(int oct, int axis) { return ((oct >> axis) & 1) != 0 ? -1 : 1; }

// The render parameters, uploaded once per frame (std140), in float: the casters need no double
// (docs/ALGORITHMS.md section 8).
struct CasterParams {
    vec4 eye;          // Camera::eye
    vec4 forward;      // Camera basis
    vec4 right;
    vec4 up;
    vec4 gridOrigin;   // GridGeometry::origin
    vec4 spacing;      // GridGeometry::spacing
    vec2 ertDepth;     // the optical depth where opacity reaches ert (render/span.h terminationDepth) as a float
                       // pair: x + y, y below half an ulp of x (+inf, 0 for no early termination)
    float halfHeight;  // Camera::halfHeight
    float dt;          // step in world units
    float loopProbe;   // kLoopProbeTrips
    ivec4 dims;        // voxels per axis
    ivec2 imageSize;    // width, height
    uint maxIterations;
    ivec4 octantSlot[2];  // ACD/EACD: z-slab of each octant in the field image, -1 when not uploaded
    vec4 light;           // xyz: unit direction toward the light; w = 1 when set, 0 for a headlight
    vec4 material;        // ambient, diffuse, specular, shininess
    vec4 background;      // rgb
    // How a sample is classified (core/scalar_classification.h, shaders/transfer_lookup.h): the transfer table's
    // first scalar, 1 / its step (exactly 1 for an integer volume) and its last entry's index; the gradient length
    // at or below which a sample is flat (no normal).
    float tableLo;
    float tableInverseStep;
    float tableLastEntry;
    float flatGradient;
    float isoValue;       // Blend::Iso's scalar
    float opacityLength;  // the length over which the TF gives its opacity (ScalarClassification::referenceStep):
                          // MIP, MinIP and average show the TF's opacity at their value as alpha
    float flatAbove;      // MIP and MinIP start and end their running value at these (render/flat_table_ends.h)
    float flatBelow;
    ivec4 blockLevelZ;    // the blocks caster: the first z texel of each level of blocks (render/block_extrema.h)
    // What clips every ray (render/ray_setup.h RayClip), in grid coordinates: the crop box's faces (0 and dims
    // without a crop) and the planes, xyz: n, w: c, keeping dot(n, p) >= c (shaders/clip_planes.h).
    ivec4 cropLo;
    ivec4 cropHi;
    vec4 clipPlanes[kMaxClipPlanes];
    int clipPlaneCount;
    int jitter;  // 1: each ray's lattice starts late by its pixel's fraction of a step (jitter.h)
    int labelLastEntry;  // the label table's last entry (label_lookup.h labelEntry)
    int opaqueValues;    // 1: MIP, MinIP and average show their value's colour opaque (RenderSettings::opaqueValues)
    float frustumShift;  // Camera::shift: an off-axis (stereo) eye's horizontal window offset, 0 otherwise
    int gradientExponentBase;  // the stored gradients' base exponent (gradient_code.h)
    int hierBlockShift;        // the hier caster: its blocks' edge is 1 << hierBlockShift voxels
    // A stereo left eye's bands (stereo_reprojection.h): the disparity scale, 1 / the focus distance, the first
    // band's near disparity and the bands' width in pixels; their number.
    vec4 stereoBands;
    int stereoBandCount;
    int rayCounts;  // 1: write each pixel's OutPixel::counts (RenderSettings::rayCounts)
};

// One dispatch renders one brick of one tile for the rays of one pass (push constants).
struct TilePush {
    ivec2 tileOrigin;   // first pixel of this dispatch
    ivec2 tileSize;     // pixels of this dispatch (the output buffers hold one tile)
    ivec4 brickLo;      // the brick's core (inclusive, global voxels): samples whose voxel lies in it are this
    ivec4 brickHi;      // dispatch's
    ivec4 imageLo;      // global voxel of texel (0, 0, 0) of the brick's images
    ivec4 imageDims;    // texels of one slab of the brick's images
    int firstDispatch;  // 1: start every ray of the tile
    int lastDispatch;   // 1: a ray left unfinished was in no pass (a bug)
    int passAxes;       // this pass takes the rays whose octant bits on passAxes ...
    int passSigns;      // ... are passSigns (the bricks come in an order they all cross them in)
    int groupRowStride;  // workgroup row r takes the tile's row (r groupRowStride) mod rows (workgroup_rows.h)
    int pad[3];          // to the struct's std430 size
};

// A ray's state between the dispatches of its bricks (std430; shaders/brick_state.glsl).
struct RayState {
    vec4 composite;  // premultiplied colour, transmittance 1 - alpha; the other blends: their running value in x
                     // (MIP, MinIP) or their sum as a float pair in xy (average)
    vec2 depth;      // optical depth so far, a float pair as CasterParams::ertDepth
    uint k;          // the next lattice sample: also the samples the spans so far represent
    uint iterations;
    uint flags;      // kFailed, kCutShort, kIsoInside, kIsoHit
    // Composite, a stereo left eye (stereo_reprojection.h): the first moment of its opacity over t so far, whether
    // it gathered anything in its current band, and its record at the current band's near end (the moment, then
    // the premultiplied colour and transmittance); the mask of the bands so far in which its segment is used.
    float moment;
    uint bandGathered;
    float bandStartMoment;
    vec4 bandStart;
    uint bandMask;
};

// A pixel's result (std430): the colour's four floats' bits, then the samples and the iteration count with its
// flags. The casters write the two to buffers of their own, the counts only when asked, so that a frame without them
// copies half the bytes back (on a discrete GPU that copy is a fixed cost of every frame); a stereo left eye's
// pixels are kept whole for the reprojection. Whole vectors: llvmpipe stores a buffer lane by lane and word by word,
// which made three outputs of seven 32-bit words a seventh of a leaping caster's time.
struct OutPixel {
    uvec4 colour;
    uvec4 counts;  // x: samples, y: iterations | flags, zw: the float bits of the pixel's contributing depth
                   // interval [t_near, t_far] along its ray (+inf, +inf: nothing; shaders/stereo_reprojection.h);
                   // composite: +inf, +inf (a stereo left eye carries its depths in its bands)
};

// A ray of a pixel list (kBindingPixelList): its pixel (x | y << 16), the depth along the view direction from which
// it is cast (0: its whole interval; a stereo re-cast starts where the reprojection stopped vouching for it), and
// what lies in front of that depth (premultiplied rgb colour and transmittance, 16-bit unorm each: rg, then b and
// the transmittance), which the ray composites behind.
struct ListRay {
    uint pixel;
    float startDepth;
    uint frontRG;
    uint frontBT;
};

#ifdef __cplusplus
static_assert(sizeof(ListRay) == 16);
static_assert(offsetof(CasterParams, ertDepth) == 96);
static_assert(offsetof(CasterParams, halfHeight) == 104);
static_assert(offsetof(CasterParams, dims) == 128);
static_assert(offsetof(CasterParams, imageSize) == 144);
static_assert(offsetof(CasterParams, maxIterations) == 152);
static_assert(offsetof(CasterParams, octantSlot) == 160);
static_assert(offsetof(CasterParams, light) == 192);
static_assert(offsetof(CasterParams, background) == 224);
static_assert(offsetof(CasterParams, tableLo) == 240);
static_assert(offsetof(CasterParams, tableInverseStep) == 244);
static_assert(offsetof(CasterParams, tableLastEntry) == 248);
static_assert(offsetof(CasterParams, flatGradient) == 252);
static_assert(offsetof(CasterParams, isoValue) == 256);
static_assert(offsetof(CasterParams, opacityLength) == 260);
static_assert(offsetof(CasterParams, flatAbove) == 264);
static_assert(offsetof(CasterParams, flatBelow) == 268);
static_assert(offsetof(CasterParams, blockLevelZ) == 272);
static_assert(offsetof(CasterParams, cropLo) == 288);
static_assert(offsetof(CasterParams, clipPlanes) == 320);
static_assert(offsetof(CasterParams, clipPlaneCount) == 416);
static_assert(offsetof(CasterParams, jitter) == 420);
static_assert(offsetof(CasterParams, labelLastEntry) == 424);
static_assert(offsetof(CasterParams, opaqueValues) == 428);
static_assert(offsetof(CasterParams, frustumShift) == 432);
static_assert(offsetof(CasterParams, gradientExponentBase) == 436);
static_assert(offsetof(CasterParams, hierBlockShift) == 440);
static_assert(offsetof(CasterParams, stereoBands) == 448);
static_assert(offsetof(CasterParams, rayCounts) == 468);
static_assert(sizeof(CasterParams) == 480);
static_assert(offsetof(TilePush, brickLo) == 16);
static_assert(offsetof(TilePush, firstDispatch) == 80);
static_assert(sizeof(TilePush) == 112);
static_assert(offsetof(RayState, k) == 24);
static_assert(offsetof(RayState, moment) == 36);
static_assert(offsetof(RayState, bandGathered) == 40);
static_assert(offsetof(RayState, bandStart) == 48);
static_assert(offsetof(RayState, bandMask) == 64);
static_assert(sizeof(RayState) == 80);  // std430 rounds the array stride up to the vec4's 16
static_assert(sizeof(OutPixel) == 32);
}  // namespace vr::device
#endif

#endif
