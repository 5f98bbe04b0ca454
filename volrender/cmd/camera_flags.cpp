#include "volrender/cmd/camera_flags.h"

#include <cmath>

#include "core/errors.h"
#include "core/number_text.h"
#include "render/camera.h"

namespace vr {

void addCameraFlags(CLI::App& app, CameraFlags& f) {
    app.add_option("--projection", f.projection, "ortho or persp")->capture_default_str();
    app.add_option("--fov", f.fov, "vertical field of view of persp, degrees")
        ->default_str(numberText(ViewParams{}.fovDeg));
    app.add_option("--azimuth", f.azimuth, "camera turn about +y, degrees")->capture_default_str();
    app.add_option("--elevation", f.elevation, "camera turn about the right axis, degrees")->capture_default_str();
    app.add_option("--up", f.up, "view-up x,y,z, world (default: +y turned by --elevation); made orthogonal to the "
                                 "view direction, and the axis the views of --views turn about")
        ->delimiter(',')->expected(3);
    app.add_option("--center", f.center, "focal point x,y,z, world units: the point the centre pixel looks at and "
                                         "--views turn about (default: the volume centre)")
        ->delimiter(',')->expected(3);
    app.add_option("--zoom", f.zoom, "magnification as VTK's camera Zoom: > 1 magnifies (persp: the field of view "
                                     "divided by it; ortho: the parallel scale)")->capture_default_str();
}

Vec3d finiteVector(const std::vector<double>& v, const char* flag) {
    for (double x : v)
        if (!std::isfinite(x)) throw InputError(std::string(flag) + ": components must be finite numbers");
    return {v[0], v[1], v[2]};
}

ViewParams viewParams(const CameraFlags& f, int width, int height) {
    if (f.projection != "ortho" && f.projection != "persp")
        throw InputError("--projection '" + f.projection + "': expected ortho or persp");
    ViewParams view;
    view.projection = f.projection == "ortho" ? Projection::Orthographic : Projection::Perspective;
    if (f.fov && view.projection == Projection::Orthographic)
        throw InputError("--fov is the field of view of a perspective camera: it needs --projection persp");
    if (f.fov) view.fovDeg = *f.fov;
    view.azimuthDeg = f.azimuth;
    view.elevationDeg = f.elevation;
    view.width = width;
    view.height = height;
    view.zoom = f.zoom;
    if (!f.up.empty()) view.up = finiteVector(f.up, "--up");
    if (!f.center.empty()) view.centre = finiteVector(f.center, "--center");
    checkView(view);
    return view;
}

nlohmann::json cameraStatistics(const CameraFlags& f) {
    return {{"projection", f.projection}, {"fov", f.fov.value_or(ViewParams{}.fovDeg)}, {"azimuth", f.azimuth},
            {"elevation", f.elevation}, {"zoom", f.zoom}, {"up", f.up}, {"center", f.center}};
}

}  // namespace vr
