// Stereo by reprojection (docs/ALGORITHMS.md section 12), its rules stated once: the casters
// (caster.comp) record what each left pixel gathered per band of disparity (composite) or its contributing depth
// interval (the other blends), the reprojection shader (stereo_reproject.comp) moves the left eye's pixels into the
// right eye and decides which it can vouch for; the C++ side reads the same
// rules (render/stereo_camera.h, the tests). Reals are double in C++ and float in GLSL (shared_language.h).
#ifndef VR_STEREO_REPROJECTION_H
#define VR_STEREO_REPROJECTION_H

#include "device_contract.h"
#include "ray_math.h"

#ifdef __cplusplus
namespace vr::device {
#endif

// Descriptor set 0 of the reprojection shader.
VR_CONSTANT int kBindingStereoParams = 0;  // uniform: StereoParams
VR_CONSTANT int kBindingLeftPixels = 1;    // storage buffer: OutPixel per pixel of the left image, row by row
VR_CONSTANT int kBindingRightPixels = 2;   // storage buffer: the right image's colours (the reprojection), float bits
VR_CONSTANT int kBindingRecastList = 3;    // storage buffer: the count, then the right eye's rays to re-cast
                                           // (ListRay each: the casters' kBindingPixelList)
VR_CONSTANT int kBindingLeftBands = 4;     // storage texel buffer RGBA32UI: a left pixel's segment of each band
                                           // (composite; the casters' kBindingStereoBands, as texels: bandTexel)
VR_CONSTANT int kSpecIdBands = 0;          // bool: reproject the left eye's bands (composite), not its intervals
VR_CONSTANT int kReprojectGroup = 64;      // invocations per workgroup, along a row

// Bands (composite): band b holds the depths whose disparity lies in [first + b width, first + (b + 1) width), the
// first band also the nearer ones and the last the farther. A left ray keeps, at the far end of each band, what it
// has gathered from its start (a record): its premultiplied colour, its transmittance and the first moment of its
// opacity over its depth t (the sum of each part's opacity weight times its mean t). Band b's own segment is the
// difference between the records of bands b - 1 and b: its colour and opacity composited from a transparent start,
// at its opacity-weighted mean depth; the caster stores it with the ray's transmittance at the band's far end (its
// texel: packBandSegment). A span that crosses a band's far end is split there: its sigma and colour are constant
// over it, so the part before t gathers the optical depth sigma (t - t0), and its opacity's moment is its opacity
// weight times t0 + (t - t0) spanMeanFraction(sigma (t - t0)).

// The most bands a pair takes (more: the eyes are close to the volume; its right eye is cast in full). A left pixel's
// mask of the bands it was used in (bandUsed) holds one bit per band.
VR_CONSTANT int kMaxBands = 32;

// A reused piece at least this opaque hides what lies behind it, and a left ray's transmittance at most 1 - it hides
// what lies behind that point from the left eye (render/stereo_camera.h kOpaqueAlpha).
VR_CONSTANT VR_REAL kOpaqueAlpha = VR_REAL(0.98);

// Where band b ends along a ray whose direction makes `cosine` with the view direction, as 1 / t: the inverse depth
// of disparity first + (b + 1) width, times cosine. Linear in b, origin - (b + 1) perBand, with the ray's origin
// cosine (focusInverse - first / scale) and perBand cosine width / scale taken once: a ray's next band end is a
// multiplication and a subtraction away, no division. The last band, and a band that reaches infinity's disparity
// (inverse <= 0), end nowhere (bandEndBeyond).
VR_FUNCTION VR_REAL bandEndOrigin(VR_REAL scale, VR_REAL focusInverse, VR_REAL first, VR_REAL cosine) {
    return cosine * (focusInverse - first / scale);
}
VR_FUNCTION VR_REAL bandEndPerBand(VR_REAL scale, VR_REAL width, VR_REAL cosine) { return cosine * width / scale; }
VR_FUNCTION VR_REAL bandEndInverse(VR_REAL origin, VR_REAL perBand, int b) { return origin - VR_REAL(b + 1) * perBand; }

// Where band b starts: the depth along the view direction of its near disparity; 0 for the first band, which also
// holds the nearer depths, and +inf where that disparity is infinity's or beyond.
VR_FUNCTION VR_REAL bandNearDepth(VR_REAL scale, VR_REAL focusInverse, VR_REAL first, VR_REAL width, int b) {
    if (b == 0) return VR_REAL(0);
    VR_REAL inverse = bandEndInverse(bandEndOrigin(scale, focusInverse, first, VR_REAL(1)),
                                     bandEndPerBand(scale, width, VR_REAL(1)), b - 1);
    return inverse > VR_REAL(0) ? VR_REAL(1) / inverse : kInfinity;
}

// Whether t lies beyond band b's end (its inverse end as above) among `count` bands.
VR_FUNCTION bool bandEndBeyond(VR_REAL t, VR_REAL inverseEnd, int b, int count) {
    return b + 1 < count && t * inverseEnd > VR_REAL(1);
}

// Where the opacity of a homogeneous span of optical depth `depth` and opacity `opacity` (1 - e^-depth, which the
// caller has) lies on average, as a fraction of its length from its start: 1 / depth - 1 / (e^depth - 1), from 1/2
// for a faint span (its series below depth 1/64) down to 1 / depth for a dense one. 1 / (e^depth - 1) is
// (1 - opacity) / opacity: no second exponential. Exact for a span of constant sigma, so that a leap's moment is the
// sum of its samples'.
VR_FUNCTION VR_REAL spanMeanFraction(VR_REAL depth, VR_REAL opacity) {
    if (depth < VR_REAL(1) / VR_REAL(64)) return VR_REAL(0.5) - depth / VR_REAL(12);
    return VR_REAL(1) / depth - (VR_REAL(1) - opacity) / opacity;
}

// The part of a span [t0, t1) of optical depth `depth` that lies before t: its optical depth (sigma is constant over
// the span). t <= t0 gives none, t >= t1 the whole span.
VR_FUNCTION VR_REAL spanDepthBefore(VR_REAL depth, VR_REAL t0, VR_REAL t1, VR_REAL t) {
    VR_REAL f = (t - t0) / (t1 - t0);
    return depth * (f < VR_REAL(0) ? VR_REAL(0) : f < VR_REAL(1) ? f : VR_REAL(1));
}

// Where band b's segment of pixel (x, y) lies among the segments: band by band, each band's row by row, so that
// the reprojection's neighbouring invocations read neighbouring texels.
VR_FUNCTION uint bandTexel(int x, int y, int b, int width, int height) {
    return (uint(b) * uint(height) + uint(y)) * uint(width) + uint(x);
}

// Where the mask of the bands pixel (x, y) was used in lies (a plane after the bands' segments): word x % 4 of texel
// x / 4 of its row, so that the caster stores it as one word and a texel holds four neighbours' masks (a band's
// candidates for a right pixel: stereo_reproject.comp).
VR_FUNCTION uint bandMaskTexel(int x, int y, int width, int height, int count) {
    return bandTexel(x / 4, y, count, width, height);
}

// A list entry: a pixel's x and y in 16 bits each (images are at most 16384 wide).
VR_FUNCTION uint packListPixel(int x, int y) { return uint(x) | (uint(y) << 16); }

// The pair's geometry and the thresholds of the rules (std140).
struct StereoParams {
    ivec2 imageSize;
    float disparityScale;  // separation * width / (2 tan(fov/2) aspect): pixels of disparity per 1 / depth
    float focusInverse;    // 1 / the focus distance: zero disparity there
    float halfHeight;      // Camera::halfHeight (tan of half the vertical field of view)
    float leftShift;       // the left eye's Camera::shift
    float maxSpread;       // pixels: the widest disparity range over a pixel's interval that one depth stands for
                           // (composite: the bands' width)
    float faintAlpha;      // a band's segment below this opacity is faint: it lands where its neighbour's does
    float maxStep;         // the largest colour difference between the two ends of a piece that it interpolates
    float maxGap;          // pixels: neighbours reprojected farther apart than 1 + maxGap open a gap
    ivec2 window;          // right pixel x gathers the left pixels x - window.y .. x - window.x (the disparities'
                           // bounds, widened by the neighbours a piece spans)
    vec4 background;       // rgb: what a composite right pixel shows through its transmittance
    float firstDisparity;  // composite: the first band's near disparity
    int bandCount;         // composite: the number of bands
    int rowStride;         // workgroup row r takes image row (r rowStride) mod height (workgroup_rows.h)
};

// The disparity in pixels (x in the right image minus x in the left) of a point at depth z along the eyes' common
// view direction: zero at the focus distance, scale / focus for a point at infinity (z = +inf), negative in front.
VR_FUNCTION VR_REAL stereoDisparity(VR_REAL scale, VR_REAL focusInverse, VR_REAL z) {
    return scale * (focusInverse - VR_REAL(1) / z);
}

// What a left pixel tells the right eye: nothing along its ray (empty: it reprojects from infinity), one depth that
// stands for all it gathered (narrow: its interval's disparities lie within maxSpread pixels), or several (wide:
// never reused, and it hides what lies behind its near end).
VR_CONSTANT int kPixelEmpty = 0, kPixelNarrow = 1, kPixelWide = 2;
VR_FUNCTION int pixelKind(bool empty, VR_REAL nearDisparity, VR_REAL farDisparity, VR_REAL maxSpread) {
    if (empty) return kPixelEmpty;
    return farDisparity - nearDisparity <= maxSpread ? kPixelNarrow : kPixelWide;  // NaN: wide
}

// Two neighbouring left pixels (or two segments of a band) reprojected to xa <= xb are one continuous piece of what
// they show, whose colour the right pixels between them interpolate, when they landed at most 1 + maxGap pixels
// apart (farther apart they open a gap: what the left eye could not see) and their colours differ by at most maxStep
// in each channel (a steeper step is detail the interpolation would blur, or that the right eye's own samples place
// elsewhere: an edge, the sampling lattice's rings on a surface). Anything else is re-cast.
VR_FUNCTION bool continuousSpan(VR_REAL xa, VR_REAL xb, VR_REAL maxGap, VR_REAL colourStep, VR_REAL maxStep) {
    return xb - xa <= VR_REAL(1) + maxGap && colourStep <= maxStep;
}

// Two left pixels' piece (the other blends) also needs neither to be wide.
VR_FUNCTION bool continuousPiece(int kindA, int kindB, VR_REAL xa, VR_REAL xb, VR_REAL maxGap, VR_REAL colourStep,
                                 VR_REAL maxStep) {
    return kindA != kPixelWide && kindB != kPixelWide && continuousSpan(xa, xb, maxGap, colourStep, maxStep);
}

// A right pixel keeps the reprojection when the nearest of what covers it is a continuous piece that either is
// opaque or has nothing else non-empty behind it (what lies behind a translucent piece shows through in the right
// eye); `others` counts the other non-empty covers.
VR_FUNCTION bool reuseCover(bool continuous, VR_REAL pieceAlpha, VR_REAL opaqueAlpha, int others) {
    return continuous && (pieceAlpha >= opaqueAlpha || others == 0);
}

#ifdef __cplusplus
static_assert(offsetof(StereoParams, disparityScale) == 8);
static_assert(offsetof(StereoParams, window) == 40);
static_assert(offsetof(StereoParams, background) == 48);
static_assert(sizeof(StereoParams) == 80);
}  // namespace vr::device
#else
ivec2 unpackListPixel(uint p) { return ivec2(int(p & 0xffffu), int(p >> 16)); }

// A left pixel's segment of a band, as one texel (kBindingLeftBands): its premultiplied colour and opacity (16-bit
// unorm each: they lie in [0, 1]), the disparity of its mean depth (meaningless where its opacity is 0) and the ray's
// transmittance at the band's far end. The caster stores it as a buffer's uvec4 (llvmpipe stores an image's texel
// at a higher cost), the reprojection reads it as a texel buffer's texel (llvmpipe loads a buffer lane by lane and
// word by word, a texel buffer's texels as one gather; it reads five per band per pixel).
struct BandSegment {
    vec4 colour;
    float disparity;
    float transmittance;
};

uvec4 packBandSegment(BandSegment s) {
    return uvec4(packUnorm2x16(s.colour.rg), packUnorm2x16(s.colour.ba), floatBitsToUint(s.disparity),
                 floatBitsToUint(s.transmittance));
}

BandSegment unpackBandSegment(uvec4 t) {
    return BandSegment(vec4(unpackUnorm2x16(t.x), unpackUnorm2x16(t.y)), uintBitsToFloat(t.z), uintBitsToFloat(t.w));
}

// A segment is hidden when the left ray's transmittance at its band's far end is at most 1 - kOpaqueAlpha.
bool segmentHidden(float transmittance) { return transmittance <= 1.0 - kOpaqueAlpha; }

// A segment (as its texel) is used when it has content (any colour or opacity) or is hidden. A band whose candidate
// segments for a right pixel all lie in the image and none of which is used adds nothing to that pixel: they are
// faint, so each piece lands whole at the band's middle and composites nothing, and none is hidden. The caster keeps
// a mask of the bands in which each left pixel's segment is used and stores only those segments; the reprojection
// skips the bands it does not need and takes an unused segment as nothing, unread.
bool bandUsed(uvec4 t) { return (t.x | t.y) != 0u || segmentHidden(uintBitsToFloat(t.w)); }

// Band b's segment from the ray's records at its near end (start) and far end (end: rgb premultiplied colour, a
// transmittance; with the moments of opacity over t); `cosine` turns t into depth along the view direction. A band
// the ray gathered nothing in has none. Two divisions (llvmpipe divides at a tenth of its multiplications' rate): the
// disparity of mean depth z = moment / (opacity weight) is scale (1 / focus - weight / moment).
BandSegment bandSegment(vec4 start, float startMoment, vec4 end, float endMoment, bool gathered, float cosine,
                        float scale, float focusInverse) {
    BandSegment s;
    float inverse = 1.0 / max(start.a, 1e-30);
    s.colour = clamp(vec4((end.rgb - start.rgb) * inverse, 1.0 - end.a * inverse), 0.0, 1.0);
    if (!gathered || start.a <= 0.0) s.colour = vec4(0.0);
    s.disparity = scale * (focusInverse - (start.a - end.a) / ((endMoment - startMoment) * cosine));
    s.transmittance = end.a;
    return s;
}
#endif

#endif
