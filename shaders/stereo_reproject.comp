// The right eye of a stereo pair from the left eye's pixels (docs/ALGORITHMS.md section 12; the rules:
// stereo_reprojection.h). One invocation per right pixel, a workgroup per stretch of a row: the parallel form of the
// scanline pass. The workgroup reprojects the left pixels of its window once, into shared memory; each pixel then
// gathers, from the left pixels of its row whose disparity could bring them to it, every piece that covers
// its centre: a pair of neighbours reprojected on both sides of it (a continuous piece, or a gap), and the span of
// a wide pixel's disparities. The nearest cover wins (overlaps keep the nearest); a continuous winner gives its
// interpolated colour, anything else (a gap, a wide pixel, nothing at all) puts the pixel on the re-cast list.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "ray_math.h"
#include "stereo_reprojection.h"

layout(local_size_x = kReprojectGroup) in;

layout(set = 0, binding = kBindingStereoParams, std140) uniform Params { StereoParams params; };
layout(set = 0, binding = kBindingLeftPixels, std430) readonly buffer LeftPixels { OutPixel leftPixel[]; };
layout(set = 0, binding = kBindingRightPixels, std430) writeonly buffer RightPixels { OutPixel rightPixel[]; };
layout(set = 0, binding = kBindingRecastList, std430) buffer RecastList { uint recastCount; uint recastPixel[]; };

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
    float u = imagePlaneU(centre, params.imageSize.x, params.imageSize.y, params.halfHeight) + params.leftShift;
    float cosine = inversesqrt(1.0 + u * u + vSquared);  // of the ray's angle to the view direction
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

void main() {
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
    uint index = uint(y * width + x);
    rightPixel[index].colour = floatBitsToUint(reuse ? bestColour : vec4(0.0));
    rightPixel[index].counts = uvec4(0u);
    if (!reuse) recastPixel[atomicAdd(recastCount, 1u)] = packListPixel(x, y);
}
