// The casters of docs/ALGORITHMS.md section 5 and the blends of section 11 in one loop: renderCpu's trace in GLSL.
// Specialization constants pick the caster, the blend, the sampling, the shading and the scalars' type, so each
// variant compiles to a pipeline without the others' branches. One invocation per pixel of one tile and one brick
// (brick_state.glsl: a ray's state carries over from brick to brick, so bricks change no leap). Every sample is
// classified from the scalars through the transfer table, as the CPU reference classifies it; each span is shaded
// once, at its first sample (equal to shading every sample for a directional light or headlight when thresholds
// are 0).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "blend.h"
#include "device_contract.h"
#include "gradient_code.h"
#include "label_lookup.h"
#include "stereo_reprojection.h"
#include "transfer_lookup.h"

// The third size: the pieces each composite ray is cast in (PIECES below), 1 for whole rays.
layout(local_size_x = kWorkgroupSize, local_size_y = kWorkgroupSize, local_size_z_id = kSpecIdPieces) in;

// The caster and the blend are fixed per module: shaders/CMakeLists.txt builds one for each pair the renderer
// accepts. As specialization constants they left every caster in one module (200 KB), which lavapipe translated and
// optimized whole for each pipeline: 0.1 s on one core against 0.06 s for one pair's module (0.03 s plain, below).
const int CASTER = VR_CASTER;
// Whether the composite sample loop tests its condition at the end of each trip (main): llvmpipe runs a loop's body
// once more, under an empty mask, after a test at the start of a trip has let the last ray of a SIMD batch out.
const bool TEST_AT_END = CASTER == kACD || CASTER == kEACD;
layout(constant_id = kSpecIdTrilinear) const bool TRILINEAR = false;
layout(constant_id = kSpecIdShading) const bool SHADING = true;
// false: the volume is one brick, rendered in one dispatch per tile, so no ray state is carried (llvmpipe would
// run the state's loads and stores, lane by lane, even where a uniform condition turns them off).
layout(constant_id = kSpecIdBricked) const bool BRICKED = true;
// The camera's projection: llvmpipe would compute both cameras' rays for every pixel.
layout(constant_id = kSpecIdPerspective) const bool PERSPECTIVE = false;
// Which of the scalar images holds the volume (its type).
layout(constant_id = kSpecIdScalarType) const int SCALAR_TYPE = kScalarFloat32;
// What a ray makes of its samples (blend.h): composite, or a running value of the scalar that the blocks caster
// leaps by.
const int BLEND = VR_BLEND;
// Cast the pixels of a list (a stereo pair's re-casts), in chunks of a tile's invocations, instead of a tile.
layout(constant_id = kSpecIdPixelList) const bool PIXEL_LIST = false;
// Leaps take the samples their margin proves (docs/ALGORITHMS.md section 8), unchecked: the margin is a small part of
// a step in this frame (render/ray_setup.h leapsByTheMargin).
layout(constant_id = kSpecIdMarginLeaps) const bool MARGIN_LEAPS = false;
#if VR_PLAIN
// A plain module (composite without a label map, stored gradients or a stereo left eye's bands, as most renders
// are): half the size of the full one, so lavapipe makes its pipeline in about half the time.
const int LABELS = kNoLabels;
const bool STORED_GRADIENTS = false;
const bool STEREO_BANDS = false;
#else
// Whether a label map is beside the scalars, and the type of its labels (label_lookup.h).
layout(constant_id = kSpecIdLabels) const int LABELS = kNoLabels;
// Shade by each voxel's stored gradient (gradient_code.h) instead of central differences of the scalars.
layout(constant_id = kSpecIdStoredGradients) const bool STORED_GRADIENTS = false;
// The left eye of a stereo pair: record what the ray gathered at the far end of each band (stereo_reprojection.h).
layout(constant_id = kSpecIdStereoBands) const bool STEREO_BANDS = false;
#endif
// Composite rays in pieces (a stereo pair's re-casts on a discrete GPU; frames on request): the workgroup's third
// size cuts each of its rays into that many stretches of nearly equal length, cast by separate invocations, so that
// no ray's whole length lies on one invocation's chain of dependent loads. Each gathers its stretch alone (its
// premultiplied colour and optical depth), and the ray's first composites them front to back (end of main). A volume
// of bricks carries whole rays from brick to brick instead.
layout(constant_id = kSpecIdPiecewise) const bool PIECEWISE = false;  // the workgroup's third size is above 1
const bool PIECES = BLEND == kBlendComposite && !BRICKED && !STEREO_BANDS && PIECEWISE;
// Each piece's colour and optical depth, and its samples and iterations with its failures.
shared vec4 pieceColour[kWorkgroupSize * kWorkgroupSize * kMostPieces];
shared uvec2 pieceCounts[kWorkgroupSize * kWorkgroupSize * kMostPieces];

#include "caster_params.glsl"
#include "ray_setup.glsl"
#include "span.glsl"
#include "brick_state.glsl"
#include "extent_code.glsl"

// Storage images (volrender/vulkan/gpu_buffer.h): llvmpipe loads them more cheaply than texelFetch.
// The scalars in the volume's own type: integers packed into words, or floats; the other image is unused.
layout(set = 0, binding = kBindingScalarWords, r32ui) uniform readonly uimage3D scalarWords;
layout(set = 0, binding = kBindingScalarsFloat, r32f) uniform readonly image3D scalarsFloat;
// The field, bound by its format: PC (r), ACD (r per octant slab) and joint8 EACD in R8, log16 EACD in R16, exact
// EACD in RGBA8 (rgb); the other two are unused.
layout(set = 0, binding = kBindingField8, r8ui) uniform readonly uimage3D field8;
layout(set = 0, binding = kBindingField16, r16ui) uniform readonly uimage3D field16;
layout(set = 0, binding = kBindingFieldRGBA8, rgba8ui) uniform readonly uimage3D fieldRGBA8;
// Each block's scalar range over the whole volume, lo and hi in one texel, for the blocks caster
// (render/block_extrema.h).
layout(set = 0, binding = kBindingBlockExtrema, rg32f) uniform readonly image3D blockExtrema;
// The transfer table: entry i classifies the scalar tableLo + i step (rgb colour, a: extinction sigma). A texel
// buffer (volrender/vulkan/gpu_buffer.h TexelTable), as the label table.
layout(set = 0, binding = kBindingTransferTable, rgba32f) uniform readonly imageBuffer transferTable;
layout(set = 0, binding = kBindingOutColours, std430) writeonly buffer OutColours { uvec4 outColour[]; };
layout(set = 0, binding = kBindingOutCounts, std430) writeonly buffer OutCounts { uvec4 outCounts[]; };
// The label map's labels packed into words, and its table: entry l for label l (rgb colour, a: extinction sigma).
layout(set = 0, binding = kBindingLabelWords, r32ui) uniform readonly uimage3D labelWords;
layout(set = 0, binding = kBindingLabelTable, rgba32f) uniform readonly imageBuffer labelTable;
layout(set = 0, binding = kBindingPixelList, std430) readonly buffer PixelList { uint listCount; ListRay listRay[]; };
layout(set = 0, binding = kBindingGradients, r32ui) uniform readonly uimage3D gradients;
layout(set = 0, binding = kBindingStereoBands, std430) writeonly buffer StereoBands { uvec4 segments[]; };

// Whether t lies beyond the ray's band `band`, whose end is inverseEnd as 1 / t (stereo_reprojection.h).
bool bandEndBeyond(float t, float inverseEnd, int band) {
    return bandEndBeyond(t, inverseEnd, band, params.stereoBandCount);
}

// Stores band `band`'s segment of `pixel` where it is used (bandUsed: the reprojection reads no other); its bit in
// the pixel's mask of used bands.
uint storeSegment(ivec2 pixel, int band, BandSegment s) {
    uvec4 texel = packBandSegment(s);
    if (!bandUsed(texel)) return 0u;
    segments[bandTexel(pixel.x, pixel.y, band, params.imageSize.x, params.imageSize.y)] = texel;
    return 1u << band;
}

// Band `band`'s segment of `pixel`, from the ray's records at the band's near end (start) and far end.
uint storeBandSegment(ivec2 pixel, int band, vec4 start, float startMoment, vec4 end, float endMoment, bool gathered,
                      float cosine) {
    return storeSegment(pixel, band, bandSegment(start, startMoment, end, endMoment, gathered, cosine,
                                                 params.stereoBands.x, params.stereoBands.y));
}

// The pixel's mask of used bands, one word (bandMaskTexel): llvmpipe stores a buffer lane by lane and word by word.
void storeBandMask(ivec2 pixel, uint mask) {
    uint texel = bandMaskTexel(pixel.x, pixel.y, params.imageSize.x, params.imageSize.y, params.stereoBandCount);
    segments[texel][pixel.x & 3] = mask;
}

// Composites a span over [t0, t1) (its shaded colour, opacity and optical depth as a float pair) into the ray's
// colour (with what its float sum has lost so far: Kahan), transmittance and optical depth, and for a stereo left
// eye into the first moment of its opacity over t.
void compositeSpan(vec3 shaded, float spanAlpha, vec2 spanDepth, float t0, float t1, inout vec3 colour,
                   inout vec3 colourLost, inout float transmittance, inout vec2 depth, inout float moment) {
    if (spanAlpha > 0.0) {
        precise float w = transmittance * spanAlpha;
        precise vec3 added = shaded * w - colourLost;
        precise vec3 total = colour + added;
        colourLost = (total - colour) - added;
        colour = total;
        if (STEREO_BANDS) moment += w * (t0 + (t1 - t0) * spanMeanFraction(spanDepth.x, spanAlpha));
        depth = addPair(depth, spanDepth);
        // From the optical depth, not by subtracting w: 1 - 1e-9 is 1 in float, which would keep the weights of
        // 10^7 samples of opacity 1e-9 at transmittance 1 (0.5 % too much colour in all).
        transmittance = 1.0 - spanOpacity(depth.x + depth.y);
    }
}

uvec4 loadField(ivec3 texel) {
    if (CASTER == kEACD && EACD_CODE == kLog16) return imageLoad(field16, texel);
    if (CASTER == kEACD && EACD_CODE == kExact) return imageLoad(fieldRGBA8, texel);
    return imageLoad(field8, texel);
}

// Where the integer of `bits` bits at brick texel t lies among an image's words: the word's texel, and the
// integer's first bit in it (device_contract.h wordShift).
ivec4 wordOf(ivec3 t, int bits) {
    int shift = wordShift(bits);
    return ivec4(t.x >> shift, t.yz, (t.x & ((1 << shift) - 1)) * bits);
}

// The scalar of a global voxel (exact in float for the integer types).
float loadScalar(ivec3 v) {
    ivec3 texel = brickTexel(v);
    if (SCALAR_TYPE == kScalarFloat32) return imageLoad(scalarsFloat, texel).r;
    int bits = scalarBits(SCALAR_TYPE);
    ivec4 w = wordOf(texel, bits);
    uint word = imageLoad(scalarWords, w.xyz).r;
    return SCALAR_TYPE == kScalarInt16 ? float(bitfieldExtract(int(word), w.w, bits))
                                       : float(bitfieldExtract(word, w.w, bits));
}

// Classification of a scalar (docs/ALGORITHMS.md section 2): the transfer table's entries around it, interpolated;
// rgb colour, a: extinction sigma. A scalar on an entry (every voxel of an integer volume) takes it exactly. The
// colour is read with sigma for every sample: reading it only where a span is composited cost leaping casters
// 10 to 20 % more on llvmpipe (masked loads), although most of their samples in air are not composited.
vec4 classify(float scalar) {
    float t = tableCoordinate(scalar, params.tableLo, params.tableInverseStep, params.tableLastEntry);
    int i = int(t);
    int j = min(i + 1, int(params.tableLastEntry));
    float w = t - float(i);
    vec4 a = imageLoad(transferTable, i), b = imageLoad(transferTable, j);
    return vec4(interpolate(a.r, b.r, w), interpolate(a.g, b.g, w), interpolate(a.b, b.b, w),
                interpolate(a.a, b.a, w));
}

// The label of a global voxel, and its entry in the label table.
int loadLabel(ivec3 v) {
    int bits = LABELS == kLabelsUInt8 ? 8 : 16;
    ivec4 w = wordOf(brickTexel(v), bits);
    return int(bitfieldExtract(imageLoad(labelWords, w.xyz).r, w.w, bits));
}
vec4 labelClass(int label) { return imageLoad(labelTable, labelEntry(label, params.labelLastEntry)); }

// A sample's classification with the label of its voxel v mixed in (label_lookup.h): never interpolated.
vec4 labelled(vec4 c, ivec3 v) {
    if (LABELS == kNoLabels) return c;
    vec4 l = labelClass(loadLabel(v));
    return vec4(labelledChannel(c.a, c.r, l.a, l.r), labelledChannel(c.a, c.g, l.a, l.g),
                labelledChannel(c.a, c.b, l.a, l.b), labelledSigma(c.a, l.a));
}

// The gradient of label l's smoothed indicator at voxel v (label_lookup.h indicatorGradient, there in double).
vec3 indicatorGradient(ivec3 v, int l) {
    vec3 g = vec3(0.0);
    for (int a = 0; a < 3; ++a) {
        int lo = max(v[a] - 1, 0), hi = min(v[a] + 1, params.dims[a] - 1);
        if (hi == lo) continue;
        int b = (a + 1) % 3, c = (a + 2) % 3;
        float sum = 0.0;
        for (int ob = -1; ob <= 1; ++ob)
            for (int oc = -1; oc <= 1; ++oc) {
                ivec3 p = v;
                p[b] = clamp(v[b] + ob, 0, params.dims[b] - 1);
                p[c] = clamp(v[c] + oc, 0, params.dims[c] - 1);
                ivec3 pl = p, ph = p;
                pl[a] = lo;
                ph[a] = hi;
                float w = indicatorWeight(ob) * indicatorWeight(oc);
                sum += w * (float(loadLabel(ph) == l) - float(loadLabel(pl) == l));
            }
        g[a] = sum / (float(kIndicatorWeightSum) * float(hi - lo) * params.spacing[a]);
    }
    return g;
}

// core/gradient.h's central difference along one axis between voxels lo <= hi of a row: 0 where they are one voxel
// (an axis of a single voxel). It multiplies by the inverse of the axis' spacing, which the compiler finds once for
// all 24 differences of a shaded sample, where a division each cost a frame 4-7 % on llvmpipe.
float centralDifference(float sLo, float sHi, int lo, int hi, float inverseSpacing) {
    return hi > lo ? (sHi - sLo) * (hi - lo > 1 ? 0.5 * inverseSpacing : inverseSpacing) : 0.0;
}

// Voxel v's stored gradient.
vec3 storedGradient(ivec3 v) {
    return unpackGradient(imageLoad(gradients, brickTexel(v)).r, params.gradientExponentBase);
}

// The scalar gradient at voxel v: central differences, one-sided at the volume's border (core/gradient.h).
vec3 voxelGradient(ivec3 v) {
    if (STORED_GRADIENTS) return storedGradient(v);
    vec3 g;
    for (int a = 0; a < 3; ++a) {
        ivec3 lo = v, hi = v;
        lo[a] = max(v[a] - 1, 0);
        hi[a] = min(v[a] + 1, params.dims[a] - 1);
        g[a] = centralDifference(loadScalar(lo), loadScalar(hi), lo[a], hi[a], 1.0 / params.spacing[a]);
    }
    return g;
}

// A cell-centred trilinear sample's footprint: voxel u's value sits at u + 0.5, clamped to the edge outside. Corner
// (X, Y, Z) is voxel (X ? hi : lo) per axis, its scalar sXYZ; f the weights of the hi corners.
struct Footprint {
    ivec3 lo, hi;  // hi = lo + 1 per axis, or lo (clamped at the volume's edge)
    vec3 f;
    float s000, s100, s010, s110, s001, s101, s011, s111;
};

Footprint footprintAt(vec3 p) {
    precise vec3 q = p - vec3(0.5);
    ivec3 base = floorVoxel(q);
    precise vec3 f = q - vec3(base);
    Footprint fp;
    fp.lo = clampVoxel(base);
    fp.hi = clampVoxel(base + 1);
    fp.f = f;
    ivec3 a = fp.lo, b = fp.hi;
    fp.s000 = loadScalar(ivec3(a.x, a.y, a.z));
    fp.s100 = loadScalar(ivec3(b.x, a.y, a.z));
    fp.s010 = loadScalar(ivec3(a.x, b.y, a.z));
    fp.s110 = loadScalar(ivec3(b.x, b.y, a.z));
    fp.s001 = loadScalar(ivec3(a.x, a.y, b.z));
    fp.s101 = loadScalar(ivec3(b.x, a.y, b.z));
    fp.s011 = loadScalar(ivec3(a.x, b.y, b.z));
    fp.s111 = loadScalar(ivec3(b.x, b.y, b.z));
    return fp;
}

// The interpolated scalar: x first, then y, then z (transfer_lookup.h), as the CPU reference blends.
float footprintScalar(Footprint fp) {
    return trilinearBlend(fp.s000, fp.s100, fp.s010, fp.s110, fp.s001, fp.s101, fp.s011, fp.s111, fp.f.x, fp.f.y,
                          fp.f.z);
}

// The central differences along axis `a` at a row's two footprint corners c0 <= c1 (the row's other coordinates
// are row's), whose scalars s0 and s1 are loaded already: (at c0, at c1). Only the voxels before c0 and after c1
// are loaded; in the volume's interior c1 = c0 + 1 is c0's upper neighbour and c0 is c1's lower one. Where the
// corners are one voxel (the volume's edge) both take the difference around it.
vec2 rowDifferences(ivec3 row, int a, int c0, int c1, float s0, float s1) {
    int n = params.dims[a];
    float inverseSpacing = 1.0 / params.spacing[a];
    ivec3 before = row, after = row;
    before[a] = max(c0 - 1, 0);
    after[a] = min(c1 + 1, n - 1);
    float sBefore = loadScalar(before), sAfter = loadScalar(after);
    bool apart = c1 != c0;
    int hi0 = apart ? c1 : after[a], lo1 = apart ? c0 : before[a];
    float sHi0 = apart ? s1 : sAfter, sLo1 = apart ? s0 : sBefore;
    return vec2(centralDifference(sBefore, sHi0, before[a], hi0, inverseSpacing),
                centralDifference(sLo1, sAfter, lo1, after[a], inverseSpacing));
}

// Gradients at a footprint's eight corners (x fastest) blended as its scalar is, component by component.
vec3 blendCorners(vec3 g000, vec3 g100, vec3 g010, vec3 g110, vec3 g001, vec3 g101, vec3 g011, vec3 g111, vec3 f) {
    vec3 g;
    for (int i = 0; i < 3; ++i)
        g[i] = trilinearBlend(g000[i], g100[i], g010[i], g110[i], g001[i], g101[i], g011[i], g111[i], f.x, f.y, f.z);
    return g;
}

// The gradient of a trilinear sample: each component the corners' central differences blended as the scalar is
// (24 loads beyond the corners': a row's outer neighbours per axis).
vec3 footprintGradient(Footprint fp) {
    ivec3 a = fp.lo, b = fp.hi;
    vec3 f = fp.f;
    if (STORED_GRADIENTS)
        return blendCorners(storedGradient(ivec3(a.x, a.y, a.z)), storedGradient(ivec3(b.x, a.y, a.z)),
                            storedGradient(ivec3(a.x, b.y, a.z)), storedGradient(ivec3(b.x, b.y, a.z)),
                            storedGradient(ivec3(a.x, a.y, b.z)), storedGradient(ivec3(b.x, a.y, b.z)),
                            storedGradient(ivec3(a.x, b.y, b.z)), storedGradient(ivec3(b.x, b.y, b.z)), f);
    // Rows along x at (Y, Z): (g0YZ, g1YZ); along y at (X, Z): (gX0Z, gX1Z); along z at (X, Y): (gXY0, gXY1).
    vec2 x00 = rowDifferences(ivec3(a.x, a.y, a.z), 0, a.x, b.x, fp.s000, fp.s100);
    vec2 x10 = rowDifferences(ivec3(a.x, b.y, a.z), 0, a.x, b.x, fp.s010, fp.s110);
    vec2 x01 = rowDifferences(ivec3(a.x, a.y, b.z), 0, a.x, b.x, fp.s001, fp.s101);
    vec2 x11 = rowDifferences(ivec3(a.x, b.y, b.z), 0, a.x, b.x, fp.s011, fp.s111);
    vec2 y00 = rowDifferences(ivec3(a.x, a.y, a.z), 1, a.y, b.y, fp.s000, fp.s010);
    vec2 y10 = rowDifferences(ivec3(b.x, a.y, a.z), 1, a.y, b.y, fp.s100, fp.s110);
    vec2 y01 = rowDifferences(ivec3(a.x, a.y, b.z), 1, a.y, b.y, fp.s001, fp.s011);
    vec2 y11 = rowDifferences(ivec3(b.x, a.y, b.z), 1, a.y, b.y, fp.s101, fp.s111);
    vec2 z00 = rowDifferences(ivec3(a.x, a.y, a.z), 2, a.z, b.z, fp.s000, fp.s001);
    vec2 z10 = rowDifferences(ivec3(b.x, a.y, a.z), 2, a.z, b.z, fp.s100, fp.s101);
    vec2 z01 = rowDifferences(ivec3(a.x, b.y, a.z), 2, a.z, b.z, fp.s010, fp.s011);
    vec2 z11 = rowDifferences(ivec3(b.x, b.y, a.z), 2, a.z, b.z, fp.s110, fp.s111);
    return vec3(trilinearBlend(x00.x, x00.y, x10.x, x10.y, x01.x, x01.y, x11.x, x11.y, f.x, f.y, f.z),
                trilinearBlend(y00.x, y10.x, y00.y, y10.y, y01.x, y11.x, y01.y, y11.y, f.x, f.y, f.z),
                trilinearBlend(z00.x, z10.x, z01.x, z11.x, z00.y, z10.y, z01.y, z11.y, f.x, f.y, f.z));
}

// The unit gradient, or zero (flat) where it is no longer than the classification's flat length.
vec3 normalOf(vec3 g) {
    float len = length(g);
    return len > params.flatGradient ? g / len : vec3(0.0);
}

// The unit normal of a composited sample at voxel v (footprint fp where trilinear): the scalars' gradient, or
// where v's label shapes the normal (label_lookup.h) its smoothed indicator's, blended over the footprint as the
// scalar is, flat only where it is 0.
vec3 sampleNormal(Footprint fp, ivec3 v) {
    if (LABELS != kNoLabels) {
        int l = loadLabel(v);
        if (labelShapesNormal(labelClass(l).a)) {
            vec3 g;
            if (!TRILINEAR) {
                g = indicatorGradient(v, l);
            } else {
                ivec3 a = fp.lo, b = fp.hi;
                g = blendCorners(indicatorGradient(ivec3(a.x, a.y, a.z), l), indicatorGradient(ivec3(b.x, a.y, a.z), l),
                                 indicatorGradient(ivec3(a.x, b.y, a.z), l), indicatorGradient(ivec3(b.x, b.y, a.z), l),
                                 indicatorGradient(ivec3(a.x, a.y, b.z), l), indicatorGradient(ivec3(b.x, a.y, b.z), l),
                                 indicatorGradient(ivec3(a.x, b.y, b.z), l), indicatorGradient(ivec3(b.x, b.y, b.z), l),
                                 fp.f);
            }
            float len = length(g);
            return len > 0.0 ? g / len : vec3(0.0);
        }
    }
    return normalOf(TRILINEAR ? footprintGradient(fp) : voxelGradient(v));
}

// A span's colour as composited: shaded by the normal of its first sample (voxel v, footprint fp) where it shows
// something.
vec3 shadedSpan(vec3 colour, float alpha, Footprint fp, ivec3 v, vec3 toEye, vec3 toLight) {
    return SHADING && alpha > 0.0 ? shade(colour, sampleNormal(fp, v), toEye, toLight) : colour;
}

// A leap from sample k (voxel v) to the far faces of v's box of extents ext in the ray's octant (ACD, EACD, blocks,
// hier): the samples it wants without and with the margin of docs/ALGORITHMS.md section 8, and the box.
struct BoxLeap {
    float wanted, wantedWithMargin;
    VoxelBox box;
};

BoxLeap octantBoxLeap(GridRay g, RayInterval iv, uint k, ivec3 v, int oct, ivec3 ext, LeapSlack slack) {
    vec3 exits = boxExitsT(g, v, oct, ext);
    float t = latticeT(iv, k);
    return BoxLeap(boxLeapSamples(exits, vec3(0.0), t), boxLeapSamples(exits, slack.boxExit, t),
                   octantBox(v, oct, ext));
}

// The first z texel of a level in the block extrema image. Selected, not indexed: an index into the uniforms' copy
// would make llvmpipe keep all of it in memory.
int levelZ(int level) {
    ivec4 z = params.blockLevelZ;
    return level == 0 ? z.x : level == 1 ? z.y : level == 2 ? z.z : z.w;
}

// A ray's state before its first sample: nothing composited, or the blend's running value before any scalar.
vec4 initialComposite() {
    if (keepsExtreme(BLEND)) return vec4(initialRunning(BLEND, params.flatAbove, params.flatBelow));
    if (BLEND == kBlendAverage) return vec4(0.0);
    return vec4(vec3(0.0), 1.0);
}

// What MIP, MinIP and average show (docs/ALGORITHMS.md section 11): the value's TF colour at the TF's opacity, or
// opaque (a grey window), over the background; the background alone for a ray without samples.
vec4 shownValue(float value, bool sampled) {
    if (!sampled) return vec4(params.background.rgb, 0.0);
    vec4 c = classify(value);
    float alpha = params.opaqueValues != 0 ? 1.0 : spanOpacity(c.a * params.opacityLength);
    return vec4(c.rgb * alpha + params.background.rgb * (1.0 - alpha), alpha);
}

// Sample k's voxel v, counted as an iteration; false where the sample lies outside this dispatch's brick (the next
// brick's pass takes it) or the ray has reached the iteration cap (failed).
bool enterSample(GridRay g, RayInterval iv, uint k, out ivec3 v, inout uint iterations, inout bool failed) {
    v = sampleVoxel(g, iv, k);
    if (BRICKED && !inBrick(v)) return false;
    failed = ++iterations > params.maxIterations;
    return !failed;
}

// Folds a sample's scalar into the blend's running values (blend.h); for the iso-surface, whether the surface lies
// between the last sample and this one (the side is then left at the last sample's; the hit is refined below).
bool foldSample(float scalar, uint k, inout float running, inout vec2 sum, inout bool inside) {
    if (BLEND == kBlendIso) {
        if (k > 0u && isoInside(scalar, params.isoValue) != inside) return true;
        inside = isoInside(scalar, params.isoValue);
    }
    running = foldRunning(BLEND, running, scalar);
    if (BLEND == kBlendAverage) sum = addPair(sum, vec2(scalar, 0.0));
    return false;
}

// MIP and MinIP: no later sample can change what the ray shows (blend.h runningSettled).
bool settled(float running) { return runningSettled(BLEND, running, params.flatAbove, params.flatBelow); }

// Whether a ray's loop (composite's or the blocks caster's) goes on to sample k: the ray is in this dispatch, within
// its cap, before its end and its early termination (composite), and not yet hit or settled (the other blends).
bool sampling(bool mine, bool failed, bool hit, uint k, uint kEnd, vec2 depth, float running) {
    return mine && !failed && !hit && k < kEnd && pairLess(depth, params.ertDepth) && !settled(running);
}

// The scalar at grid position p, sampled as the loop samples it.
float scalarAt(vec3 p) { return TRILINEAR ? footprintScalar(footprintAt(p)) : loadScalar(clampVoxel(floorVoxel(p))); }

// The iso-surface between samples k - 1 and k, on opposite sides of the iso-value: the interval halved
// kIsoBisections times by the side of the interpolated scalar at its middle, the hit at the middle of the last one
// (renderCpu's isoSurface). Its TF colour, shaded with the normal there; tHit: where it lies along the ray.
vec3 isoSurface(GridRay g, RayInterval iv, uint k, vec3 toEye, vec3 toLight, out float tHit) {
    float before = latticeT(iv, k - 1u), beyond = latticeT(iv, k);
    bool insideBeyond = isoInside(scalarAt(rayAt(g, beyond)), params.isoValue);
    for (int i = 0; i < kIsoBisections; ++i) {
        precise float middle = (before + beyond) * 0.5;
        if (isoInside(scalarAt(rayAt(g, middle)), params.isoValue) == insideBeyond) beyond = middle;
        else before = middle;
    }
    precise float t = (before + beyond) * 0.5;
    tHit = t;
    vec3 p = rayAt(g, t);
    vec3 colour = classify(params.isoValue).rgb;
    if (!SHADING) return colour;
    vec3 gradient = TRILINEAR ? footprintGradient(footprintAt(p)) : voxelGradient(clampVoxel(floorVoxel(p)));
    return shade(colour, normalOf(gradient), toEye, toLight);
}

void main() {
    copyUniforms();
    // llvmpipe runs the 8 invocations of a row of this 8x8 workgroup as one SIMD batch, for as long as its
    // slowest ray takes: each batch takes a 4x2 block of pixels, whose rays stay closer together than an 8x1 row's.
    uvec2 l = gl_LocalInvocationID.xy;
    uvec2 inGroup = uvec2((l.x & 3u) | ((l.y & 1u) << 2), (l.y & ~1u) | (l.x >> 2));
    // Rows of workgroups interleaved over the tile (volrender/vulkan/workgroup_rows.h): llvmpipe's threads each
    // take a contiguous run of workgroups.
    uvec2 group = uvec2(gl_WorkGroupID.x, gl_WorkGroupID.y * uint(tile.groupRowStride) % gl_NumWorkGroups.y);
    ivec2 local = ivec2(group * uint(kWorkgroupSize) + inGroup);
    // An invocation without a pixel ends here, or, where rays are cast in pieces, casts nothing and reaches the
    // workgroup's barrier (below) with the others.
    bool hasPixel = PIXEL_LIST || all(lessThan(local, tile.tileSize));
    if (!PIECES && !hasPixel) return;
    ivec2 pixel = tile.tileOrigin + local;
    uint outIndex = uint(local.y * tile.tileSize.x + local.x);
    ListRay listed = ListRay(0u, 0.0, 0u, 0u);
    if (PIXEL_LIST) {
        // This dispatch's chunk of the list starts at entry tileOrigin.x; each workgroup takes 64 consecutive
        // entries, so that a SIMD batch takes neighbouring rays that start at the same depth (the list is sorted so:
        // volrender/vulkan/stereo_render.cpp).
        outIndex = (group.y * gl_NumWorkGroups.x + group.x) * uint(kWorkgroupSize * kWorkgroupSize) +
                   l.y * uint(kWorkgroupSize) + l.x;
        uint entry = uint(tile.tileOrigin.x) + outIndex;
        hasPixel = outIndex < uint(tile.tileSize.x * tile.tileSize.y) && entry < listCount;
        if (!PIECES && !hasPixel) return;
        if (hasPixel) listed = listRay[entry];
        pixel = unpackListPixel(listed.pixel);
    }

    vec3 direction;
    GridRay g = cameraGridRay(float(pixel.x) + 0.5, float(pixel.y) + 0.5, direction);
    RayInterval iv = jitteredInterval(intersectGrid(g), pixel);
    uint kCount = hasPixel ? latticeCount(iv) : 0u;
    float cosine = dot(direction, params.forward.xyz);  // t to depth along the view direction
    // A listed ray cast from a depth takes its samples from the first at or beyond it, behind what lies in front.
    uint kFirst = PIXEL_LIST && listed.startDepth > 0.0 ? firstSampleFrom(iv, listed.startDepth / cosine, kCount)
                                                        : 0u;
    uint pieces = PIECES ? gl_WorkGroupSize.z : 1u, piece = PIECES ? gl_LocalInvocationID.z : 0u;
    uint kStart = kFirst + pieceStart(kCount - kFirst, piece, pieces);
    uint kEnd = kFirst + pieceStart(kCount - kFirst, piece + 1u, pieces);
    LeapSlack slack = leapSlack(g, iv);
    int oct = rayOctant(g);
    // Selected, not indexed: llvmpipe reads an array at a varying index lane by lane.
    ivec4 slots = oct < 4 ? params.octantSlot[0] : params.octantSlot[1];
    int slot = (oct & 1) == 0 ? ((oct & 2) == 0 ? slots.x : slots.z) : ((oct & 2) == 0 ? slots.y : slots.w);
    vec3 toEye = -direction;
    vec3 toLight = params.light.w != 0.0 ? params.light.xyz : toEye;

    bool missingOctant = (CASTER == kACD || CASTER == kEACD || CASTER == kHier) && slot < 0 && kCount > 0u;
    bool firstDispatch = !BRICKED || tile.firstDispatch != 0, lastDispatch = !BRICKED || tile.lastDispatch != 0;
    // The ray's first piece starts behind what lies in front of it (nothing, unless listed so).
    vec4 start = initialComposite();
    if (PIXEL_LIST && BLEND == kBlendComposite && piece == 0u)
        start = vec4(unpackUnorm2x16(listed.frontRG), unpackUnorm2x16(listed.frontBT));
    vec2 frontDepth = vec2(BLEND == kBlendComposite && start.a < 1.0 ? -log(start.a) : 0.0, 0.0);  // optical
    RayState state = firstDispatch ? RayState(start, frontDepth, kStart, 0u, missingOctant ? kFailed : 0u, 0.0, 0u,
                                              0.0, vec4(0.0, 0.0, 0.0, 1.0), 0u)
                                   : loadRayState(outIndex);
    vec3 colour = state.composite.rgb;
    // What the colour's float sum has lost so far (Kahan): the primitive caster adds one sample at a time, and
    // 10^4 samples of opacity 1e-9 would otherwise lose 1e-4 of the colour, 10^7 of them 7 % (the stiff cases).
    vec3 colourLost = vec3(0.0);
    float transmittance = state.composite.a;  // 1 - alpha, for the colour's weights
    vec2 depth = state.depth;                 // the optical depth: alpha and early ray termination
    // The other blends' running values (blend.h): the largest or smallest scalar, the sum as a float pair (whose
    // sums agree however the samples are grouped into leaps), the iso-surface's side of the last sample.
    float running = state.composite.x;
    vec2 sum = state.composite.xy;
    bool inside = (state.flags & kIsoInside) != 0u, hit = (state.flags & kIsoHit) != 0u;
    uint iterations = state.iterations;
    bool failed = (state.flags & kFailed) != 0u;
    uint k = state.k;
    // A stereo left eye's bands: the band the ray is in and where it ends (the bands before it are stored: its
    // spans so far crossed their ends), the first moment of its opacity over t, whether it gathered anything in its
    // band, and its record at the band's near end.
    float moment = state.moment;
    bool bandGathered = state.bandGathered != 0u;
    vec4 bandStart = state.bandStart;
    float bandStartMoment = state.bandStartMoment;
    uint bandMask = state.bandMask;
    int band = 0;
    float endInverse = 0.0, bandOrigin = 0.0, perBand = 0.0;
    if (STEREO_BANDS) {
        float tk = latticeT(iv, k);
        vec4 b = params.stereoBands;
        bandOrigin = bandEndOrigin(b.x, b.y, b.z, cosine);
        perBand = bandEndPerBand(b.x, b.w, cosine);
        while (k > 0u && bandEndBeyond(tk, bandEndInverse(bandOrigin, perBand, band), band)) ++band;
        endInverse = bandEndInverse(bandOrigin, perBand, band);
    }
    // This dispatch continues the ray when the ray is in this pass and its next sample lies in this brick; it
    // then runs until a sample leaves the brick (a leap may cross bricks: the next brick's pass finds it there).
    bool mine = k < kEnd && (!BRICKED || (rayInPass(oct) && inBrick(sampleVoxel(g, iv, k))));
    if (!mine && !firstDispatch && !lastDispatch) return;
    // MIP and MinIP with blocks: the running value starts at the probe samples (blend.h), which a volume of one brick
    // holds (a bricked one starts without).
    if (CASTER == kBlocks && keepsExtreme(BLEND) && !BRICKED && kCount > 0u)
        for (int i = 0; i < kProbes; ++i, ++iterations)
            running = foldRunning(BLEND, running, scalarAt(samplePosition(g, iv, probeSample(i, kCount))));
    // A stereo left eye leaves the sample loop at a span that reaches its band's far end, and stores the bands'
    // segments and composites that span after it: llvmpipe runs a loop's body at least once, so that code in the
    // sample loop would cost every sample; here it costs once per band end that a SIMD batch of rays reaches.
    bool crossing = false;  // the span below reaches the band's far end
    uint n = 1u;
    vec3 shaded, spanColour;
    vec2 spanDepth;
    float spanAlpha, t0, t1;
    bool shown = false;  // the primitive caster's sample below shows something: shaded and composited out of its loop
    ivec3 spanVoxel;
    Footprint spanFootprint;
    // The blocks caster (the other blends only). Each trip of the outer loop leaps block after block in the leap
    // loop, one lookup each (the coarsest block that cannot change the result; average adds its one value n times),
    // until a finest block that could change it, whose samples the sample loop then takes one by one to its far faces
    // (blockEnd). Each loop holds only its own code: llvmpipe runs a loop's body for all lanes of a SIMD batch while
    // any of them needs it, so a lookup in the sample loop cost nearly every sample, and a sample beside the lookup
    // every leap. An iteration is a leap or a sample; a sampled block's lookup and first sample are one.
    if (CASTER == kBlocks) {
        // Tested at the end of each trip: llvmpipe runs a loop's body once more, under an empty mask, after its last
        // ray in a SIMD batch has left it by a test at the start of a trip. A ray's optical depth stays 0 here.
        if (sampling(mine, failed, hit, k, kEnd, depth, running)) do {
            // Leaps until a block that could change the result, which sample k (voxel v) starts.
            ivec3 v;
            vec2 finest;   // the finest block's scalar range at sample k
            bool entered;  // sample k is this dispatch's, and within the iteration cap
            do {
                entered = enterSample(g, iv, k, v, iterations, failed);
                if (!entered) break;
                int size = 0;  // the edge of the block leapt over; 0: none
                float value = 0.0;
                for (int level = 0; level < kBlockLevels; ++level) {
                    int shift = kBlockShift + level;  // shifts, not divisions: llvmpipe divides lane by lane
                    if (size != (level == 0 ? 0 : 1 << (shift - 1))) break;  // the finer block could not be leapt
                    ivec3 block = ivec3(v.xy >> shift, levelZ(level) + (v.z >> shift));
                    vec2 range = imageLoad(blockExtrema, block).rg;
                    if (level == 0) finest = range;
                    if (blockSkipped(BLEND, range.x, range.y, running, params.isoValue, inside)) {
                        size = 1 << shift;
                        value = range.x;
                    }
                }
                int edge = size > 0 ? size : kBlockSize;
                ivec3 ext = ivec3(blockExtent(v.x, octantSign(oct, 0), edge),
                                  blockExtent(v.y, octantSign(oct, 1), edge),
                                  blockExtent(v.z, octantSign(oct, 2), edge));
                BoxLeap b = octantBoxLeap(g, iv, k, v, oct, ext, slack);
                n = leapCount(g, iv, k, kEnd, b.wanted, b.wantedWithMargin, b.box);
                if (size == 0) break;  // the block could change the result: sampled below
                if (BLEND == kBlendAverage) sum = addPair(sum, exactProduct(float(n), value));
                k += n;
            } while (k < kEnd);
            if (!entered || k >= kEnd) break;
            for (uint blockEnd = k + n;;) {
                float scalar = TRILINEAR ? footprintScalar(footprintAt(samplePosition(g, iv, k))) : loadScalar(v);
                hit = foldSample(scalar, k, running, sum, inside);
                if (hit || ++k >= blockEnd || settled(running)) break;
                // MIP and MinIP: once the running value passes the block's range, its other samples cannot change
                // it, and the ray leaps to the block's far faces (the leap's lookup was this block's).
                if (blockSkipped(BLEND, finest.x, finest.y, running, params.isoValue, inside)) {
                    k = blockEnd;
                    break;
                }
                if (!enterSample(g, iv, k, v, iterations, failed)) break;
            }
        } while (sampling(mine, failed, hit, k, kEnd, depth, running));
    } else do {
        // ACD and EACD test at the end of each trip, as the blocks loop above does (5 % faster frames on llvmpipe);
        // the others at its start (PC and hier were 4-7 % slower tested at the end). One body: with the test at the
        // start, `do { if (!sampling) break; ... } while (true)` is a `for (; sampling; k += n)`.
        n = 1u;
        if (!TEST_AT_END || sampling(mine, failed, hit, k, kEnd, depth, running)) do {
            if (!TEST_AT_END && !sampling(mine, failed, hit, k, kEnd, depth, running)) break;
            ivec3 v;
            if (!enterSample(g, iv, k, v, iterations, failed)) break;
            // The sample's scalar. Composite classifies it (docs/ALGORITHMS.md section 2) and takes its gradient only
            // where its span is composited and shaded, below: a transparent span needs none.
            Footprint fp;
            if (TRILINEAR) fp = footprintAt(samplePosition(g, iv, k));
            float scalar = TRILINEAR ? footprintScalar(fp) : loadScalar(v);
            hit = foldSample(scalar, k, running, sum, inside);
            if (hit) break;
            if (BLEND != kBlendComposite) continue;  // the primitive caster: one sample (n stays 1)
            vec4 s = labelled(classify(scalar), v);  // rgb colour, a: sigma
            precise float sampleDepth = s.a * params.dt;

            // What the leap wants without and with the margin of docs/ALGORITHMS.md section 8.
            float wanted = 1.0, wantedWithMargin = 1.0;
            VoxelBox box = VoxelBox(v, v);
            if (CASTER == kPC) {
                int r = int(loadField(brickTexel(v)).r);
                wanted = pcLeapSamples(r, g, 0.0);
                wantedWithMargin = pcLeapSamples(r, g, slack.ball);
                box = chebyshevBall(v, r);
            } else if (CASTER == kACD || CASTER == kEACD) {
                uvec4 f = loadField(fieldTexel(v, slot));
                // A stored 0 would be a corrupt field; 1 (this voxel) is always true.
                ivec3 ext = CASTER == kACD ? max(ivec3(1), ivec3(f.r)) : decodeExtents(f);
                BoxLeap b = octantBoxLeap(g, iv, k, v, oct, ext, slack);
                wanted = b.wanted;
                wantedWithMargin = b.wantedWithMargin;
                box = b.box;
            } else if (CASTER == kHier) {
                // The code of v's block in the ray's octant; a mixed block steps one sample, a homogeneous one leaps to
                // the far faces of its box of blocks.
                int shift = params.hierBlockShift;
                uint code = imageLoad(field16, blockTexel(v, slot, shift)).r;
                if ((code & kHomogeneousBlock) != 0u) {
                    ivec3 blocks = decodeExtents(uvec4(code));
                    ivec3 ext = ivec3(blockBoxExtent(v.x, octantSign(oct, 0), shift, blocks.x),
                                      blockBoxExtent(v.y, octantSign(oct, 1), shift, blocks.y),
                                      blockBoxExtent(v.z, octantSign(oct, 2), shift, blocks.z));
                    BoxLeap b = octantBoxLeap(g, iv, k, v, oct, ext, slack);
                    wanted = b.wanted;
                    wantedWithMargin = b.wantedWithMargin;
                    box = b.box;
                }
            }
            // The primitive caster steps one sample (n stays 1): it needs no termination count and no leap count.
            if (CASTER != kPrimitive) {
                float termination = samplesToTermination(depth, sampleDepth);
                if (TRILINEAR) wanted = trilinearLeapSamples(wanted, box);
                if (TRILINEAR) wantedWithMargin = trilinearLeapSamples(wantedWithMargin, box);
                n = leapCount(g, iv, k, kEnd, min(wanted, termination), min(wantedWithMargin, termination), box);
            }

            // The span's depth n sigma dt, exact as a pair: the same sum as n single samples'.
            spanDepth = CASTER == kPrimitive ? vec2(sampleDepth, 0.0) : exactProduct(float(n), sampleDepth);
            spanAlpha = spanOpacity(spanDepth.x);
            t0 = latticeT(iv, k);
            t1 = latticeT(iv, k + n);
            crossing = STEREO_BANDS && bandEndBeyond(t1, endInverse, band);
            // A transparent span that ends a band the ray gathered nothing in, and no more, moves on to the next band
            // here: that band starts with the same record, and this one's segment is unused (unless the ray is hidden:
            // stereo_reprojection.h bandUsed), so leaving the loop for it only cost the others in the SIMD batch.
            if (crossing && !bandGathered && !(spanAlpha > 0.0) && !segmentHidden(transmittance) &&
                !bandEndBeyond(t1, bandEndInverse(bandOrigin, perBand, band + 1), band + 1)) {
                endInverse = bandEndInverse(bandOrigin, perBand, ++band);
                crossing = false;
            }
            // The primitive caster shades a sample that shows something out of this loop, below, with a span that
            // reaches a stereo band's far end: llvmpipe runs both sides of a branch under a mask, so shading here
            // cost its every transparent sample too (a primitive frame 30 % longer). A leaping caster shades here:
            // out of the loop, the rays of a SIMD batch wait for each other at their spans, and a stereo left eye
            // would shade again at every band end, which cost more.
            if (CASTER != kPrimitive) shaded = shadedSpan(s.rgb, spanAlpha, fp, v, toEye, toLight);
            shown = CASTER == kPrimitive && spanAlpha > 0.0;
            if (crossing || shown) {
                spanColour = s.rgb;
                spanFootprint = fp;
                spanVoxel = v;
                break;
            }
            if (CASTER == kPrimitive) continue;  // nothing to composite
            if (STEREO_BANDS && spanAlpha > 0.0) bandGathered = true;
            compositeSpan(shaded, spanAlpha, spanDepth, t0, t1, colour, colourLost, transmittance, depth, moment);
        } while (TEST_AT_END ? sampling(mine, failed, hit, k += n, kEnd, depth, running) : (k += n, true));
        if (!crossing && !shown) break;
        shown = false;
        if (CASTER == kPrimitive)
            shaded = shadedSpan(spanColour, spanAlpha, spanFootprint, spanVoxel, toEye, toLight);
        // A stereo left eye stores the segments of the bands whose far end the span reaches, from its record
        // there: what it gathered up to there, the span split where the band ends (however many samples the span
        // leaps). `crossing` is the loop's first test (tested at the end of each trip, as the blocks loop's).
        if (crossing) do {
            float bandEnd = 1.0 / endInverse;
            precise float part = spanDepthBefore(spanDepth.x, t0, t1, bandEnd);
            float partAlpha = spanOpacity(part);
            float w = transmittance * partAlpha;
            vec4 end = vec4(colour - colourLost + shaded * w, transmittance - w);
            float endMoment = moment + w * (t0 + max(bandEnd - t0, 0.0) * spanMeanFraction(part, partAlpha));
            bandGathered = bandGathered || (spanAlpha > 0.0 && bandEnd > t0);
            bandMask |= storeBandSegment(pixel, band, bandStart, bandStartMoment, end, endMoment, bandGathered, cosine);
            bandStart = end;
            bandStartMoment = endMoment;
            bandGathered = false;
            endInverse = bandEndInverse(bandOrigin, perBand, ++band);
        } while (bandEndBeyond(t1, endInverse, band));
        if (STEREO_BANDS && spanAlpha > 0.0) bandGathered = true;
        compositeSpan(shaded, spanAlpha, spanDepth, t0, t1, colour, colourLost, transmittance, depth, moment);
        k += n;
        crossing = false;
    } while (true);

    // A settled ray represents the rest of its samples, as a leap over a block that cannot change it does.
    if (settled(running)) k = kEnd;

    // Some drivers end loops on their own: llvmpipe stops every loop of an invocation once 65535 iterations have run
    // in all of them, which would silently shorten a long ray. A loop whose trip count (2) the compiler cannot
    // know runs short afterwards exactly when that happened.
    int probe = 0;
    for (float i = 0.0; i < params.loopProbe; i += 1.0) ++probe;
    uint flags = state.flags | (probe < kLoopProbeTrips ? kCutShort : 0u);
    bool unfinished = k < kEnd && !hit && (BLEND != kBlendComposite || pairLess(depth, params.ertDepth));
    if (lastDispatch && unfinished) failed = true;  // in no pass: a bug
    if (failed) flags |= kFailed;
    flags = (flags & ~kIsoInside) | (inside ? kIsoInside : 0u) | (hit ? kIsoHit : 0u);
    // The next brick's dispatch reads this state; after the last one, nothing does.
    colour -= colourLost;
    vec4 carried = BLEND == kBlendComposite ? vec4(colour, transmittance)
                   : BLEND == kBlendAverage ? vec4(sum, 0.0, 0.0)
                                            : vec4(running, 0.0, 0.0, 0.0);
    if (!lastDispatch)
        storeRayState(outIndex, RayState(carried, depth, k, iterations, flags, moment, bandGathered ? 1u : 0u,
                                         bandStartMoment, bandStart, bandMask));
    // After the ray's last span, the bands it did not reach end with all it gathered: the band it ended in holds
    // the rest, the bands after it nothing.
    if (STEREO_BANDS && lastDispatch && band < params.stereoBandCount) {
        bandMask |= storeBandSegment(pixel, band, bandStart, bandStartMoment, vec4(colour, transmittance), moment,
                                     bandGathered, cosine);
        // Those hold nothing: used only where the ray ended hidden.
        for (++band; band < params.stereoBandCount && segmentHidden(transmittance); ++band)
            bandMask |= storeSegment(pixel, band, BandSegment(vec4(0.0), 0.0, transmittance));
        storeBandMask(pixel, bandMask);
    }

    uint failure = flags & (kFailed | kCutShort), samples = k - kStart;
    if (PIECES) {
        // The ray's pieces, composited front to back by its first into the whole ray's colour and optical depth;
        // their counts summed, the failures of any.
        uint first = (l.y * uint(kWorkgroupSize) + l.x) * pieces;
        pieceColour[first + piece] = vec4(colour, depth.x + depth.y);
        pieceCounts[first + piece] = uvec2(samples, iterations | failure);
        barrier();
        if (piece != 0u) return;
        colour = vec3(0.0);
        depth = vec2(0.0);
        samples = iterations = failure = 0u;
        for (uint j = 0u; j < pieces; ++j) {
            vec4 c = pieceColour[first + j];
            uvec2 n = pieceCounts[first + j];
            colour += (1.0 - spanOpacity(depth.x)) * c.rgb;
            depth.x += c.a;
            samples += n.x;
            iterations += n.y & ~(kFailed | kCutShort);
            failure |= n.y & (kFailed | kCutShort);
        }
    }
    // Alpha from the optical depth: exact to float rounding where 1 - transmittance would cancel.
    float alpha = spanOpacity(depth.x + depth.y);
    vec4 pixelColour = vec4(colour + params.background.rgb * (1.0 - alpha), alpha);
    if (BLEND == kBlendMIP || BLEND == kBlendMinIP) pixelColour = shownValue(running, kCount > 0u);
    if (BLEND == kBlendAverage) pixelColour = shownValue((sum.x + sum.y) / float(kCount), kCount > 0u);
    // The other blends depend on every sample of the ray (MIP, MinIP, average) or on the surface's hit (iso);
    // composite carries its depths in its bands.
    vec2 interval = vec2(kInfinity);
    if (BLEND != kBlendComposite && BLEND != kBlendIso && kCount > 0u) interval = vec2(iv.tEntry, iv.tExit);
    if (BLEND == kBlendIso) {
        float tHit = kInfinity;
        pixelColour = hit ? vec4(isoSurface(g, iv, k, toEye, toLight, tHit), 1.0) : vec4(params.background.rgb, 0.0);
        interval = vec2(tHit);
    }
    if (!hasPixel) return;
    uvec4 colourBits = floatBitsToUint(pixelColour);
    if (failure != 0u) colourBits.a = failureAlphaBits(failure);
    outColour[outIndex] = colourBits;
    if (params.rayCounts != 0) outCounts[outIndex] = uvec4(samples, iterations | failure, floatBitsToUint(interval));
}
