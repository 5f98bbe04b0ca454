// volrender's stereo flags: the eye separation, the focus distance, how the pair is written and whether the right
// eye reuses the left's pixels.
#pragma once
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/render_settings.h"
#include "volrender/cmd/stereo_output.h"

namespace vr {

struct StereoFlags {
    std::optional<double> separation, focus;
    std::string layout = "separate";
    std::optional<std::string> reuse;  // on | off; default: on with a device, off with --cpu
};

void addStereoFlags(CLI::App& app, StereoFlags& f);

// Whether the flags ask for a pair: --focus, --stereo-layout and --stereo-reuse without --stereo are refused. Checks
// what needs no volume (render/stereo_camera.h checkStereo); InputError naming the flag.
bool checkStereoFlags(const StereoFlags& f, Projection projection, bool cpu);

StereoLayout stereoLayout(const StereoFlags& f);
// Whether the right eye reuses the left's pixels (the default on a device).
bool stereoReuse(const StereoFlags& f, bool cpu);

// The flags as --stats reports them.
nlohmann::json stereoStatistics(const StereoFlags& f, bool cpu);

}  // namespace vr
