// The right eye of a stereo pair from the left eye's pixels (docs/ALGORITHMS.md "Stereo pairs by reprojection";
// the rules: stereo_reprojection.h). One invocation per right pixel: the parallel form of the scanline pass. The
// pixel gathers, from the left pixels of its row whose disparity could bring them to it, every piece that covers
// its centre: a pair of neighbours reprojected on both sides of it (a continuous piece, or a gap), and the span of
// a wide pixel's disparities. The nearest cover wins (overlaps keep the nearest); a continuous winner gives its
// interpolated colour, anything else (a gap, a wide pixel, nothing at all) puts the pixel on the re-cast list.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "stereo_reprojection.h"
#include "numerics.glsl"

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
    float aspect = float(params.imageSize.x) / float(params.imageSize.y);
    float centre = float(x) + 0.5;
    float u = (2.0 * centre / float(params.imageSize.x) - 1.0) * params.halfHeight * aspect + params.leftShift;
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

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= params.imageSize.x || p.y >= params.imageSize.y) return;
    int width = params.imageSize.x;
    float c = float(p.x) + 0.5;
    float v = (1.0 - 2.0 * (float(p.y) + 0.5) / float(params.imageSize.y)) * params.halfHeight;
    int first = clamp(p.x - params.window.y, 0, width - 1), last = clamp(p.x - params.window.x, 0, width - 1);

    float bestDepth = kInfinity;
    bool found = false, bestContinuous = false;
    vec4 bestColour = vec4(0.0);
    float bestAlpha = 0.0;
    int nonEmpty = 0;  // covers nearer than infinity
    Reprojected a = reprojected(first, p.y, v * v);
    for (int x = first; x <= last; ++x) {
        // A wide pixel covers the right pixels its interval's disparities span, from its near end.
        if (a.kind == kPixelWide && a.xNear - 0.5 <= c && c < a.xFar + 0.5) {
            if (!found || a.depth <= bestDepth) bestContinuous = false;
            bestDepth = found ? min(bestDepth, a.depth) : a.depth;
            found = true;
            ++nonEmpty;
        }
        if (x + 1 >= width) break;
        Reprojected b = reprojected(x + 1, p.y, v * v);
        if (a.x <= c && c < b.x) {  // the piece between neighbours a and b covers c
            float depth = min(a.depth, b.depth);
            vec4 step = abs(a.colour - b.colour);
            bool continuous = continuousPiece(a.kind, b.kind, a.x, b.x, params.maxSpread,
                                              max(max(step.r, step.g), max(step.b, step.a)), params.maxStep);
            if (!found || depth < bestDepth || (depth == bestDepth && !continuous)) {
                float w = (c - a.x) / (b.x - a.x);
                bestContinuous = continuous;
                bestColour = mix(a.colour, b.colour, w);
                bestAlpha = min(a.colour.a, b.colour.a);
                bestDepth = depth;
            }
            found = true;
            if (!isinf(depth)) ++nonEmpty;
        }
        a = b;
    }
    int others = nonEmpty - (isinf(bestDepth) ? 0 : 1);
    bool reuse = found && reuseCover(bestContinuous, bestAlpha, params.opaqueAlpha, others);
    uint index = uint(p.y * width + p.x);
    rightPixel[index].colour = floatBitsToUint(reuse ? bestColour : vec4(0.0));
    rightPixel[index].counts = uvec4(0u);
    if (!reuse) recastPixel[atomicAdd(recastCount, 1u)] = packListPixel(p.x, p.y);
}
