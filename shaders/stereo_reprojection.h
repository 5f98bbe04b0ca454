// Stereo by reprojection (docs/ALGORITHMS.md section 12), its rules stated once: the casters
// (caster.comp) record each pixel's contributing depth interval, the reprojection shader (stereo_reproject.comp)
// moves the left eye's pixels into the right eye and decides which it can vouch for; the C++ side reads the same
// rules (render/stereo_camera.h, the tests). Reals are double in C++ and float in GLSL (shared_language.h).
#ifndef VR_STEREO_REPROJECTION_H
#define VR_STEREO_REPROJECTION_H

#include "device_contract.h"

#ifdef __cplusplus
namespace vr::device {
#endif

// Descriptor set 0 of the reprojection shader.
VR_CONSTANT int kBindingStereoParams = 0;  // uniform: StereoParams
VR_CONSTANT int kBindingLeftPixels = 1;    // storage buffer: OutPixel per pixel of the left image, row by row
VR_CONSTANT int kBindingRightPixels = 2;   // storage buffer: OutPixel per pixel of the right image (the reprojection)
VR_CONSTANT int kBindingRecastList = 3;    // storage buffer: the count, then the right pixels to re-cast (the
                                           // casters' kBindingPixelList)
VR_CONSTANT int kReprojectGroup = 64;      // invocations per workgroup, along a row

// A composite ray's opacity alpha is counted in levels of 1 / kOpacityLevels: its contributing depth interval runs
// from the span where alpha first reaches a level to the end of the last span that raised it to a new one. What lies
// outside it adds less than one level to alpha before the interval (and one after); a ray that never reaches a level
// carries no interval (+inf, +inf), like a ray that misses the volume.
VR_CONSTANT int kOpacityLevels = 16;
VR_FUNCTION int opacityLevel(VR_REAL alpha) { return int(alpha * VR_REAL(kOpacityLevels)); }

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
    float opaqueAlpha;     // a reused piece at least this opaque hides what lies behind it
    float maxStep;         // the largest colour difference between the two ends of a piece that it interpolates
    float maxGap;          // pixels: neighbours reprojected farther apart than 1 + maxGap open a gap
    ivec2 window;          // right pixel x gathers the left pixels x - window.y .. x - window.x (the disparities'
                           // bounds, widened by the neighbours a piece spans)
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

// Two neighbouring left pixels reprojected to xa <= xb are one continuous piece of what they show, whose colour the
// right pixels between them interpolate, when neither is wide, they landed at most 1 + maxGap pixels apart
// (farther apart they open a gap: what the left eye could not see) and their colours differ by at most maxStep in
// each channel (a steeper step is detail the interpolation would blur, or that the right eye's own samples place
// elsewhere: an edge, the sampling lattice's rings on a surface). Anything else is re-cast.
VR_FUNCTION bool continuousPiece(int kindA, int kindB, VR_REAL xa, VR_REAL xb, VR_REAL maxGap, VR_REAL colourStep,
                                 VR_REAL maxStep) {
    return kindA != kPixelWide && kindB != kPixelWide && xb - xa <= VR_REAL(1) + maxGap && colourStep <= maxStep;
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
}  // namespace vr::device
#else
ivec2 unpackListPixel(uint p) { return ivec2(int(p & 0xffffu), int(p >> 16)); }
#endif

#endif
