// A stereo orbit measured (docs/BENCH.md "Stereo pairs"): each view's pair rendered with the right eye reprojected
// from the left, and both eyes rendered in full; the pair's device time against one eye's, the share of the right
// eye cast again, and the reused right eye's error against its full render.
#pragma once
#include <vector>

#include "render/stereo_camera.h"
#include "sweep/metrics/image_error.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {

// The eye separation of the benchmarks and the report: a thirtieth of the focus distance (the volume centre's),
// the photographers' rule for a comfortable depth.
constexpr double kSeparationPerFocus = 1.0 / 30;

struct StereoMeasurement {
    double pairMs = 0;          // median over the views: left eye + right eye with reuse, device time
    double oneEyeMs = 0;        // median over the views: the left eye cast in full
    double leftEyeMs = 0;       // median over the views: the reuse's left eye (cast in full, recording its bands)
    double fullPairMs = 0;      // median over the views: both eyes cast in full
    double reprojectMs = 0;     // median over the views: the reprojection alone
    double recastFraction = 0;  // mean over the views: of the right eye's pixels
    double recastInPart = 0;    // mean over the views: of the right eye's pixels, those re-cast from a depth on
    double recastWork = 0;      // the re-cast rays' loop iterations over the full right eye's, over the views: the
                                // share of its work the right eye still does, whatever the device's timing noise
    int recastPieces = 1;       // the most pieces a view's re-cast rays were cast in
    double separation = 0;      // of view 0, world units
    ErrorSummary error;         // the reused right eye against its full render, over the views
    bool leftEyesEqual = true;  // the reuse's left eye is the full render's, at every view
    std::vector<Image> reusedRight, fullRight;  // view 0's
};

// The pairs about `cameras` (perspective), each eye's separation kSeparationPerFocus of its focus distance, after
// one warm-up pair, timed without ray counts (as users render) and counted again untimed for the re-cast work. The
// orbit is timed `rounds` times over (the medians over every round's views: a steadier ratio on a noisy machine);
// errors and counts come from the first. Throws as VulkanRenderer::renderStereo does.
StereoMeasurement measureStereo(VulkanRenderer& renderer, const GpuVolume& volume, const std::vector<Camera>& cameras,
                                const RenderSettings& settings, int rounds = 1);

}  // namespace vr
