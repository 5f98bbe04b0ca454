// Stereo pairs (docs/ALGORITHMS.md section 12): two parallel perspective eyes, the separation
// apart along the view's right axis, whose off-axis frusta share their window at the focus distance (zero parallax
// there), and the disparity that moves a point from the left image to the right.
#pragma once
#include <optional>

#include "core/grid.h"
#include "render/camera.h"
#include "shaders/stereo_reprojection.h"

namespace vr {

// The reuse rules' thresholds (shaders/stereo_reprojection.h, measured by bench/stereo_bench.cpp): one depth stands
// for what spans at most kMaxSpreadPixels of disparity in an image 512 pixels tall (a composite band's width, another
// blend's narrow interval; maxSpreadPixels for other heights);
// neighbours that land more than 1 + kMaxGapPixels apart open a gap, and ones whose colours differ by more than
// kMaxColourStep (kMaxBandStep between two segments of a band) are detail; a reused piece at least kOpaqueAlpha
// opaque hides what lies behind it; a band's segment below kFaintAlpha lands where its neighbour's does. A pair
// needing more than device::kMaxBands bands (the eyes close to the volume) casts its right eye in full.
constexpr double kMaxSpreadPixels = 3;
constexpr double kMaxGapPixels = 1;
constexpr double kOpaqueAlpha = device::kOpaqueAlpha;
constexpr double kMaxColourStep = 0.05;
constexpr double kMaxBandStep = 0.2;
constexpr double kFaintAlpha = 1.0 / 64;

struct StereoPair {
    Camera left, right;
    double separation = 0, focus = 0;  // world units
};

// The checks that need no volume: a separation and a focus distance above zero, a perspective view. InputError naming
// --stereo, --focus or --projection.
void checkStereo(double separation, std::optional<double> focus, Projection projection);

// The pair about `centre` (a perspective camera): the eyes at centre.eye -/+ right separation / 2, each window shifted
// so that the frusta meet at `focus` (default: the depth of the volume centre along the view direction). InputError
// naming --stereo when the separation exceeds the focus distance, --focus when the default lies behind the eye.
StereoPair stereoPair(const Camera& centre, const GridGeometry& grid, double separation, std::optional<double> focus);

// The widest disparity that one depth stands for in an image `height` pixels tall (the field of view's pixels, as
// disparityScale counts them): kMaxSpreadPixels up to 512 pixels, and above them the same angle, up to 8 times as
// many pixels. A taller image shows the same scene over more pixels, so a depth's error moves its detail by the same
// share of it; and fewer bands keep the left eye's segments within a device's buffers (lavapipe holds 128 MiB: 7
// bands at 1024 x 1024) and the reprojection's walk short. Up to 24 pixels: a band's candidates (its pixels and one
// beyond) fit one 32-bit mask.
double maxSpreadPixels(int height);

// Pixels of disparity (x in the right image minus x in the left) per unit of focusInverse - 1 / depth.
double disparityScale(const StereoPair& pair);

// The disparity of a point at `depth` along the view direction (+inf: a point at infinity).
double disparityAt(const StereoPair& pair, double depth);

// The nearest and farthest depths along the view direction of the volume's bounding sphere (the nearest <= 0 when
// the eyes are inside it).
struct DepthRange {
    double nearest, farthest;
};
DepthRange depthRange(const StereoPair& pair, const GridGeometry& grid);

}  // namespace vr
