// volrender's command line: its flags, and the checks that need no data, so that a bad run fails before any volume
// is read.
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "preprocess/cmd/volume_flags.h"
#include "render/render_settings.h"
#include "volrender/cmd/camera_flags.h"
#include "volrender/cmd/clip_flags.h"
#include "volrender/cmd/stereo_flags.h"

namespace vr {

struct VolrenderFlags {
    std::string input, output, caster = "auto", size = "512x512";
    VolumeFlags volume;  // for a volume prepared here
    CameraFlags camera;
    ClipFlags clip;
    StereoFlags stereo;
    double step = 0.5, ert = 0.99;
    std::vector<double> light, background{0, 0, 0};
    bool noShading = false, trilinear = true, nearest = false, listDevices = false, cpu = false, quiet = false;
    bool jitter = false;
    std::string stats, heatmap, calibration, blend = "composite", gradients = "on-the-fly";
    std::optional<double> iso;
    int views = 1, device = -1;
    std::optional<int> fps;
};

void addVolrenderFlags(CLI::App& app, VolrenderFlags& f);

// Checks that need no data, and the render settings and view that the flags give. Returns whether the input is a
// prepared file (else a volume to prepare here).
bool checkVolrenderFlags(const VolrenderFlags& f, ViewParams& view, RenderSettings& s);

// A stereo pair's layout; none for a single view.
std::optional<StereoLayout> layoutOf(const VolrenderFlags& f);

// A movie's frames per second.
int movieFps(const VolrenderFlags& f);

}  // namespace vr
