// The right eye of a stereo pair from the left eye's pixels (docs/ALGORITHMS.md section 12; the rules:
// stereo_reprojection.h). One invocation per right pixel, a workgroup per stretch of a row: the parallel form of the
// scanline pass. The workgroup reprojects the left pixels of its window once, into shared memory; each pixel then
// gathers, from the left pixels of its row whose disparity could bring them to it, every piece that covers
// its centre: a pair of neighbours reprojected on both sides of it (a continuous piece, or a gap). Composite does so
// band by band, front to back, compositing each band's winning piece; the other blends once, from each left
// pixel's interval, where the span of a wide pixel's disparities covers too. The nearest cover wins (overlaps keep
// the nearest); a continuous winner gives its interpolated colour, anything else (a gap, a wide pixel, nothing at
// all, a band the left eye did not see) puts the pixel on the re-cast list.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "ray_math.h"
#include "stereo_reprojection.h"

layout(local_size_x = kReprojectGroup) in;

layout(constant_id = kSpecIdBands) const bool BANDS = false;

layout(set = 0, binding = kBindingStereoParams, std140) uniform Params { StereoParams params; };
layout(set = 0, binding = kBindingLeftPixels, std430) readonly buffer LeftPixels { OutPixel leftPixel[]; };
layout(set = 0, binding = kBindingRightPixels, std430) writeonly buffer RightPixels { OutPixel rightPixel[]; };
layout(set = 0, binding = kBindingRecastList, std430) buffer RecastList { uint recastCount; uint recastPixel[]; };
layout(set = 0, binding = kBindingLeftBands, std430) readonly buffer LeftBands { BandEnd leftBand[]; };

// The cosine of the angle between the left ray of pixel centre (px, row with v) and the view direction: t to depth.
float leftCosine(float px, float vSquared) {
    float u = imagePlaneU(px, params.imageSize.x, params.imageSize.y, params.halfHeight) + params.leftShift;
    return inversesqrt(1.0 + u * u + vSquared);
}

// A left pixel as the right eye sees it: its colour, kind, where its representative depth and its interval's ends
// land in the right row (pixel-centre coordinates), and its near depth.
struct Reprojected {
    vec4 colour;
    int kind;
    float x, xNear, xFar;
    float depth;  // +inf: empty
};

Reprojected reprojected(int x, int y, float vSquared) {
    OutPixel o = leftPixel[y * params.imageSize.x + x];
    vec2 t = uintBitsToFloat(o.counts.zw);
    float centre = float(x) + 0.5;
    float cosine = leftCosine(centre, vSquared);
    bool empty = isinf(t.x);
    float dNear = stereoDisparity(params.disparityScale, params.focusInverse, t.x * cosine);
    float dFar = stereoDisparity(params.disparityScale, params.focusInverse, t.y * cosine);
    Reprojected r;
    r.colour = uintBitsToFloat(o.colour);
    r.kind = pixelKind(empty, dNear, dFar, params.maxSpread);
    r.xNear = centre + dNear;
    r.xFar = centre + dFar;
    r.x = empty ? r.xFar : centre + 0.5 * (dNear + dFar);
    r.depth = empty ? kInfinity : t.x * cosine;
    return r;
}

// The left pixels of a workgroup's window, reprojected once and shared by its invocations, kSharedPixels at a time.
const int kSharedPixels = 512;
shared vec4 sharedColour[kSharedPixels];
shared vec4 sharedPlace[kSharedPixels];  // x, xNear, xFar, depth

// The right pixel's reprojected colour, or its place on the re-cast list.
void finish(int x, int y, bool reuse, vec4 colour) {
    uint index = uint(y * params.imageSize.x + x);
    rightPixel[index].colour = floatBitsToUint(reuse ? colour : vec4(0.0));
    rightPixel[index].counts = uvec4(0u);
    if (!reuse) recastPixel[atomicAdd(recastCount, 1u)] = packListPixel(x, y);
}

Reprojected sharedPixel(int i) {
    vec4 place = sharedPlace[i];
    Reprojected r;
    r.colour = sharedColour[i];
    r.x = place.x;
    r.xNear = place.y;
    r.xFar = place.z;
    r.depth = place.w;
    r.kind = pixelKind(isinf(r.depth), 0.0, r.xFar - r.xNear, params.maxSpread);
    return r;
}

// The other blends: one interval per left pixel.
void reprojectIntervals() {
    int width = params.imageSize.x;
    int y = int(gl_WorkGroupID.y);
    int x = int(gl_GlobalInvocationID.x);
    int groupFirst = int(gl_WorkGroupID.x) * kReprojectGroup;
    float c = float(x) + 0.5;
    float v = imagePlaneV(float(y) + 0.5, params.imageSize.y, params.halfHeight);
    // This pixel's left pixels, first .. last, and their right neighbours; the workgroup's, lo .. hi.
    int first = clamp(x - params.window.y, 0, width - 1), last = clamp(x - params.window.x, 0, width - 1);
    int end = min(last + 1, width - 1);
    int lo = clamp(groupFirst - params.window.y, 0, width - 1);
    int hi = clamp(groupFirst + kReprojectGroup - params.window.x, 0, width - 1);

    float bestDepth = kInfinity;
    bool found = false, bestContinuous = false;
    vec4 bestColour = vec4(0.0);
    float bestAlpha = 0.0;
    int nonEmpty = 0;  // covers nearer than infinity
    Reprojected a;
    for (int chunk = lo; chunk <= hi; chunk += kSharedPixels) {
        barrier();
        for (int i = int(gl_LocalInvocationID.x); i < kSharedPixels && chunk + i <= hi; i += kReprojectGroup) {
            Reprojected r = reprojected(chunk + i, y, v * v);
            sharedColour[i] = r.colour;
            sharedPlace[i] = vec4(r.x, r.xNear, r.xFar, r.depth);
        }
        barrier();
        if (x >= width) continue;
        for (int j = max(first, chunk); j <= min(end, chunk + kSharedPixels - 1); ++j) {
            Reprojected b = sharedPixel(j - chunk);
            // A wide pixel covers the right pixels its interval's disparities span, from its near end.
            if (j <= last && b.kind == kPixelWide && b.xNear - 0.5 <= c && c < b.xFar + 0.5) {
                if (!found || b.depth <= bestDepth) bestContinuous = false;
                bestDepth = found ? min(bestDepth, b.depth) : b.depth;
                found = true;
                ++nonEmpty;
            }
            if (j > first && a.x <= c && c < b.x) {  // the piece between neighbours a and b covers c
                float depth = min(a.depth, b.depth);
                vec4 step = abs(a.colour - b.colour);
                bool continuous = continuousPiece(a.kind, b.kind, a.x, b.x, params.maxGap,
                                                  max(max(step.r, step.g), max(step.b, step.a)), params.maxStep);
                if (!found || depth < bestDepth || (depth == bestDepth && !continuous)) {
                    bestContinuous = continuous;
                    bestColour = mix(a.colour, b.colour, (c - a.x) / (b.x - a.x));
                    bestAlpha = min(a.colour.a, b.colour.a);
                    bestDepth = depth;
                }
                found = true;
                if (!isinf(depth)) ++nonEmpty;
            }
            a = b;
        }
    }
    if (x >= width) return;
    int others = nonEmpty - (isinf(bestDepth) ? 0 : 1);
    bool reuse = found && reuseCover(bestContinuous, bestAlpha, params.opaqueAlpha, others);
    finish(x, y, reuse, bestColour);
}

// Composite: band by band. A left pixel's segment of a band, as shared: its colour (premultiplied rgb, alpha) and
// its disparity with its flags.
const uint kFaint = 1u, kHidden = 2u, kOutside = 4u, kContent = 8u;
shared float sharedDisparity[kSharedPixels];
shared uint sharedFlags[kSharedPixels];
// Per band: whether any of the workgroup's segments of it has content, is hidden or lies outside the image.
shared uint sharedBandMatters[kMaxBands];

// Left pixel x's segment of band b: the difference between what its ray had gathered at the band's near and far
// ends, composited from a transparent start; where it lands (its opacity-weighted mean disparity, the band's middle
// when faint); hidden when the ray's transmittance at its end is at most 1 - opaqueAlpha (the left eye did not see
// what lies behind it). A band the ray gathered nothing in is read from its pixel alone.
void loadSegment(int x, int y, int b, float vSquared, int slot) {
    int width = params.imageSize.x;
    float seen = 1.0 - params.opaqueAlpha, d = params.firstDisparity + (float(b) + 0.5) * params.maxSpread;
    uint flags = kFaint;
    vec4 colour = vec4(0.0);
    if (x < 0 || x >= width) {
        flags |= kOutside;
    } else {
        uint pixel = uint(y * width + x), gathered = leftPixel[pixel].counts.z;
        bool opaque = 1.0 - uintBitsToFloat(leftPixel[pixel].colour.a) <= seen;
        if ((gathered >> b) == 0u) {
            if (opaque) flags |= kHidden;  // past all the ray gathered: its transmittance is the pixel's
        } else if ((gathered >> b & 1u) != 0u || opaque) {
            uint i = pixel * uint(params.bandCount) + uint(b);
            BandEnd end = leftBand[i];
            vec4 start = b > 0 ? leftBand[i - 1u].composite : vec4(0.0, 0.0, 0.0, 1.0);
            float startMoment = b > 0 ? leftBand[i - 1u].moment : 0.0;
            colour.a = start.a > 0.0 ? clamp(1.0 - end.composite.a / start.a, 0.0, 1.0) : 0.0;
            colour.rgb = clamp((end.composite.rgb - start.rgb) / max(start.a, 1e-30), 0.0, 1.0);
            if (colour.a > 0.0) flags |= kContent;
            if (colour.a >= params.faintAlpha) {
                flags &= ~kFaint;
                float meanT = (end.moment - startMoment) / (start.a - end.composite.a);
                d = stereoDisparity(params.disparityScale, params.focusInverse,
                                    meanT * leftCosine(float(x) + 0.5, vSquared));
            }
            if (end.composite.a <= seen) flags |= kHidden;
        }
    }
    sharedColour[slot] = colour;
    sharedDisparity[slot] = d;
    sharedFlags[slot] = flags;
    if (flags != kFaint) sharedBandMatters[b] = 1u;
}

void reprojectBands() {
    int width = params.imageSize.x;
    int y = int(gl_WorkGroupID.y);
    int x = int(gl_GlobalInvocationID.x);
    int groupFirst = int(gl_WorkGroupID.x) * kReprojectGroup;
    float c = float(x) + 0.5;
    float v = imagePlaneV(float(y) + 0.5, params.imageSize.y, params.halfHeight);
    float bandWidth = params.maxSpread, seen = 1.0 - params.opaqueAlpha;
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    bool done = x >= width, reuse = true;
    for (int b = int(gl_LocalInvocationID.x); b < kMaxBands; b += kReprojectGroup) sharedBandMatters[b] = 0u;
    for (int b = 0; b < params.bandCount; ++b) {
        // The pieces (i, i + 1) that could cover c land their left end at or before c and their right end after it:
        // i + 0.5 + d <= c < i + 1.5 + d' with d, d' in the band.
        float near = params.firstDisparity + float(b) * bandWidth;
        int first = int(floor(float(x) - 1.0 - near - bandWidth)) + 1, last = int(floor(float(x) - near));
        int lo = int(floor(float(groupFirst) - 1.0 - near - bandWidth)) + 1;
        int hi = int(floor(float(groupFirst + kReprojectGroup - 1) - near)) + 1;
        barrier();
        for (int i = int(gl_LocalInvocationID.x); i <= hi - lo; i += kReprojectGroup)
            loadSegment(lo + i, y, b, v * v, i);
        barrier();
        // A band with nothing in it for the whole workgroup adds nothing.
        if (done || sharedBandMatters[b] == 0u) continue;
        bool found = false, best = false, bestHidden = false, clipped = false, hidden = false;
        float bestKey = kInfinity;
        vec4 bestColour = vec4(0.0);
        int covers = 0;  // pieces that are not faint at both ends
        for (int i = first; i <= last; ++i) {
            vec4 ca = sharedColour[i - lo], cb = sharedColour[i + 1 - lo];
            float da = sharedDisparity[i - lo], db = sharedDisparity[i + 1 - lo];
            uint fa = sharedFlags[i - lo], fb = sharedFlags[i + 1 - lo];
            if (((fa | fb) & kOutside) != 0u) {
                clipped = true;
                continue;
            }
            bool faintA = (fa & kFaint) != 0u, faintB = (fb & kFaint) != 0u;
            bool hiddenPiece = ((fa | fb) & kHidden) != 0u;
            hidden = hidden || hiddenPiece;
            // A faint end lands where its neighbour does (both faint: at the band's middle).
            float xa = float(i) + 0.5 + (faintA && !faintB ? db : da);
            float xb = float(i) + 1.5 + (faintB && !faintA ? da : db);
            if (!(xa <= c && c < xb)) continue;
            float key = min(faintA ? kInfinity : da, faintB ? kInfinity : db);
            if (!(faintA && faintB)) ++covers;
            vec4 step = abs(ca - cb);
            if (!found || key < bestKey) {
                float steepest = max(max(step.r, step.g), max(step.b, step.a));
                best = continuousSpan(xa, xb, params.maxGap, steepest, params.maxStep);
                bestColour = mix(ca, cb, (c - xa) / (xb - xa));
                bestHidden = hiddenPiece;
                bestKey = key;
            }
            found = true;
        }
        if (!found) {
            reuse = !clipped && !hidden;  // nothing of this band lands here, or the left eye could not tell
        } else {
            reuse = reuseCover(best, bestColour.a, params.opaqueAlpha, max(covers - 1, 0));
            colour += transmittance * bestColour.rgb;
            transmittance *= 1.0 - bestColour.a;
            reuse = reuse && !(bestHidden && transmittance > seen);
        }
        // What lies behind a right pixel this opaque adds at most 1 - opaqueAlpha of its colour.
        done = !reuse || transmittance <= seen;
    }
    if (x >= width) return;
    finish(x, y, reuse, vec4(colour + params.background.rgb * transmittance, 1.0 - transmittance));
}

void main() {
    if (BANDS) reprojectBands();
    else reprojectIntervals();
}
