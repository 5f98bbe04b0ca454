// volrender's camera flags: the projection, the turns about the volume, and VTK's view-up, focal point and zoom.
#pragma once
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/render_settings.h"

namespace vr {

struct CameraFlags {
    std::string projection = "ortho";
    std::optional<double> fov;  // persp's field of view in degrees: ViewParams' when not given
    double azimuth = 0, elevation = 0, zoom = 1;
    std::vector<double> up, center;  // empty when not given
};

void addCameraFlags(CLI::App& app, CameraFlags& f);

// x,y,z given to `flag` as a vector; InputError naming the flag unless every component is finite.
Vec3d finiteVector(const std::vector<double>& v, const char* flag);

// The view of width x height pixels the flags ask for, checked as far as it can be without the volume (checkView:
// InputError naming the flag; --fov with an orthographic projection, which has no field of view, is refused too); a
// focal point far off the volume is refused by Camera::fit.
ViewParams viewParams(const CameraFlags& f, int width, int height);

// The flags as --stats reports them.
nlohmann::json cameraStatistics(const CameraFlags& f);

}  // namespace vr
