// The right eye of a stereo pair from the left eye's pixels (docs/ALGORITHMS.md section 12; the rules:
// stereo_reprojection.h). One invocation per right pixel, a workgroup per stretch of a row: the parallel form of the
// scanline pass. Each pixel gathers, from the left pixels of its row whose disparity could bring them to it, every
// piece that covers its centre: a pair of neighbours reprojected on both sides of it (a continuous piece, or a gap).
// Composite does so band by band, front to back, compositing each band's winning piece from the segments the
// caster stored; the other blends once, from each left pixel's interval (the workgroup reprojects the left pixels
// of its window once, into shared memory), where the span of a wide pixel's disparities covers too. The nearest
// cover wins (overlaps keep the nearest); a continuous winner gives its interpolated colour, anything else (a gap,
// a wide pixel, nothing at all, a band the left eye did not see) puts the pixel on the re-cast list.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "ray_math.h"
#include "stereo_reprojection.h"

layout(local_size_x = kReprojectGroup) in;

layout(constant_id = kSpecIdBands) const bool BANDS = false;

layout(set = 0, binding = kBindingStereoParams, std140) uniform Params { StereoParams params; };
layout(set = 0, binding = kBindingLeftPixels, std430) readonly buffer LeftPixels { OutPixel leftPixel[]; };
layout(set = 0, binding = kBindingRightPixels, std430) writeonly buffer RightPixels { uvec4 rightColour[]; };
layout(set = 0, binding = kBindingRecastList, std430) buffer RecastList { uint recastCount; ListRay recastRay[]; };
layout(set = 0, binding = kBindingLeftBands, rgba32ui) uniform readonly uimageBuffer leftBands;

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

// The right pixel's reprojected colour, or its ray on the re-cast list: cast from startDepth on (0: whole), behind
// `front` (premultiplied rgb, transmittance), the reprojection of what lies before.
void finish(int x, int y, bool reuse, vec4 colour, float startDepth, vec4 front) {
    uint index = uint(y * params.imageSize.x + x);
    rightColour[index] = floatBitsToUint(reuse ? colour : vec4(0.0));
    if (!reuse)
        recastRay[atomicAdd(recastCount, 1u)] =
            ListRay(packListPixel(x, y), startDepth, packUnorm2x16(front.rg), packUnorm2x16(front.ba));
}

// The image row of this workgroup: rows interleaved over the image, as the casters' (llvmpipe's threads each take a
// contiguous run of workgroups).
int imageRow() { return int(gl_WorkGroupID.y * uint(params.rowStride) % uint(params.imageSize.y)); }

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
    int y = imageRow();
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
    bool reuse = found && reuseCover(bestContinuous, bestAlpha, kOpaqueAlpha, others);
    finish(x, y, reuse, bestColour, 0.0, vec4(0.0, 0.0, 0.0, 1.0));
}

// Composite: band by band. Left pixel x's segment of band b as the right eye sees it (the caster stored it: see
// stereo_reprojection.h bandSegment): its colour (premultiplied rgb, alpha) and where it lands (its opacity-weighted
// mean disparity, the band's middle when faint); hidden when the ray's transmittance at the band's end is at most
// 1 - kOpaqueAlpha (the left eye did not see what lies behind it); outside when x lies outside the image. Read as a
// texel by each right pixel that needs it, not shared: llvmpipe loads shared memory lane by lane, texels as one
// gather.
struct Segment {
    vec4 colour;
    float disparity;
    bool faint, hidden, outside;
};

Segment segmentAt(int x, int y, int b, bool used) {
    int width = params.imageSize.x;
    uint texel = bandTexel(clamp(x, 0, width - 1), y, b, width, params.imageSize.y);
    // An unused segment's texel is not stored (the caster leaves what an earlier pair stored there).
    BandSegment t = used ? unpackBandSegment(imageLoad(leftBands, int(texel))) : BandSegment(vec4(0.0), 0.0, 1.0);
    Segment s;
    s.outside = x < 0 || x >= width;
    s.colour = s.outside ? vec4(0.0) : t.colour;
    s.faint = s.colour.a < params.faintAlpha;
    s.disparity = s.faint ? params.firstDisparity + (float(b) + 0.5) * params.maxSpread : t.disparity;
    s.hidden = !s.outside && segmentHidden(t.transmittance);
    return s;
}

// The left pixels first .. last whose pieces (i, i + 1) could cover right pixel x's centre c in band b: they land
// their left end at or before c and their right end after it: i + 0.5 + d <= c < i + 1.5 + d' with d, d' in the band.
ivec2 bandCandidates(int x, int b) {
    float near = params.firstDisparity + float(b) * params.maxSpread;
    return ivec2(int(floor(float(x) - 1.0 - near - params.maxSpread)) + 1, int(floor(float(x) - near)));
}

// The masks of used bands of left pixels 4 t .. 4 t + 3 of row y (a mask texel; a word past the row's end is not
// this frame's).
uvec4 masksAt(int t, int y) {
    return imageLoad(leftBands, int(bandMaskTexel(4 * t, y, params.imageSize.x, params.imageSize.y, params.bandCount)));
}

// The bands that any candidate of right pixel x (of any band: the last band's first .. the first band's last + 1)
// is used in (stereo_reprojection.h bandUsed): their masks OR'ed with their texels' neighbours' (a superset costs
// only a band's work: nextBand).
uint bandsUsedNear(int x, int y) {
    int width = params.imageSize.x;
    int lo = clamp(bandCandidates(x, params.bandCount - 1).x, 0, width - 1);
    int hi = clamp(bandCandidates(x, 0).y + 1, 0, width - 1);
    uvec4 masks = uvec4(0u);
    for (int t = lo / 4; t <= hi / 4; ++t) masks |= masksAt(t, y);
    return masks.x | masks.y | masks.z | masks.w;
}

// The first band from b on that can add anything to right pixel x: one of its candidates' segments (first .. last
// + 1) lies outside the image, or is used by some candidate of x (`near`, bandsUsedNear). A band none of whose own
// candidates is used adds nothing, as if skipped (stereo_reprojection.h bandUsed), so the superset only costs a
// band's work. A loop: llvmpipe would run a skipped band's code under a mask.
int nextBand(int x, int b, uint near) {
    for (; b < params.bandCount; ++b) {
        ivec2 window = bandCandidates(x, b);
        if (window.x < 0 || window.y + 1 >= params.imageSize.x || ((near >> b) & 1u) != 0u) break;
    }
    return b;
}

// Which of left pixels first .. last of row y (those in the image) are used in band b, as bits counted from first.
uint usedIn(int first, int last, int y, int b) {
    uint used = 0u;
    for (int t = max(first, 0) / 4; t <= min(last, params.imageSize.x - 1) / 4; ++t) {
        uvec4 bits = (masksAt(t, y) >> uint(b)) & 1u;
        uint word = bits.x | (bits.y << 1) | (bits.z << 2) | (bits.w << 3);
        int base = 4 * t;
        used |= base >= first ? word << (base - first) : word >> (first - base);
    }
    return used & ((2u << uint(last - first)) - 1u);
}

void reprojectBands() {
    int width = params.imageSize.x;
    int y = imageRow();
    int x = int(gl_GlobalInvocationID.x);
    float c = float(x) + 0.5;
    float seen = 1.0 - kOpaqueAlpha;
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    bool done = x >= width, reuse = true;
    // Where the pixel's re-cast would start, and what was composited before: the band it fails in, or the first band
    // before that which nothing covered, or in which the left eye's view ended at some candidate. Such a band
    // vouches for nothing behind its cover: what the left eye could not see may lie in it (an occluder's side).
    int startBand = 0;
    bool covered = true;  // every band so far is covered, each candidate seen through, or skipped
    vec4 front = vec4(0.0, 0.0, 0.0, 1.0);
    uint near = done ? 0u : bandsUsedNear(x, y);
    // The loops test at the end of each trip: llvmpipe runs a loop's body once more, under an empty mask, after
    // its last invocation in a SIMD batch has left it by a test at the start of a trip.
    int b = -1;
    if (!done) do {
        b = nextBand(x, b + 1, near);
        if (b >= params.bandCount) break;
        ivec2 window = bandCandidates(x, b);
        int first = window.x, last = window.y;
        // Which of the candidates are used, as bits from first: an unused one's texel is not read.
        uint used = usedIn(first, last + 1, y, b);
        // No candidate used, all in the image: the band adds nothing (stereo_reprojection.h bandUsed).
        if (used == 0u && first >= 0 && last + 1 < width) continue;
        if (covered) front = vec4(colour, transmittance), startBand = b;
        bool found = false, best = false, bestHidden = false, clipped = false, hidden = false;
        float bestKey = kInfinity;
        vec4 bestColour = vec4(0.0);
        int covers = 0;  // pieces that are not faint at both ends
        Segment a = segmentAt(first, y, b, (used & 1u) != 0u);
        int i = first;  // first <= last (bandCandidates)
        do {
            Segment s = segmentAt(i + 1, y, b, ((used >> (i + 1 - first)) & 1u) != 0u);
            if (a.outside || s.outside) {
                clipped = true;
            } else {
                bool hiddenPiece = a.hidden || s.hidden;
                hidden = hidden || hiddenPiece;
                // A faint end lands where its neighbour does (both faint: at the band's middle).
                float xa = float(i) + 0.5 + (a.faint && !s.faint ? s.disparity : a.disparity);
                float xb = float(i) + 1.5 + (s.faint && !a.faint ? a.disparity : s.disparity);
                if (xa <= c && c < xb) {
                    float key = min(a.faint ? kInfinity : a.disparity, s.faint ? kInfinity : s.disparity);
                    if (!(a.faint && s.faint)) ++covers;
                    if (!found || key < bestKey) {
                        vec4 step = abs(a.colour - s.colour);
                        float steepest = max(max(step.r, step.g), max(step.b, step.a));
                        best = continuousSpan(xa, xb, params.maxGap, steepest, params.maxStep);
                        bestColour = mix(a.colour, s.colour, (c - xa) / (xb - xa));
                        bestHidden = hiddenPiece;
                        bestKey = key;
                    }
                    found = true;
                }
            }
            a = s;
        } while (++i <= last);
        covered = covered && found && !hidden;
        if (!found) {
            reuse = !clipped && !hidden;  // nothing of this band lands here, or the left eye could not tell
        } else {
            reuse = reuseCover(best, bestColour.a, kOpaqueAlpha, max(covers - 1, 0));
            colour += transmittance * bestColour.rgb;
            transmittance *= 1.0 - bestColour.a;
            reuse = reuse && !(bestHidden && transmittance > seen);
        }
        // What lies behind a right pixel this opaque adds at most 1 - kOpaqueAlpha of its colour.
        done = !reuse || transmittance <= seen;
    } while (!done);
    if (x >= width) return;
    float startDepth =
        bandNearDepth(params.disparityScale, params.focusInverse, params.firstDisparity, params.maxSpread, startBand);
    finish(x, y, reuse, vec4(colour + params.background.rgb * transmittance, 1.0 - transmittance), startDepth,
           front);
}

void main() {
    if (BANDS) reprojectBands();
    else reprojectIntervals();
}
