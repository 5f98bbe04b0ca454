// The camera convention of docs/ALGORITHMS.md section 1. The Vulkan casters build their rays on the host with this
// class and shaders/ray_setup.glsl must mirror Camera::ray() exactly (same pixel mapping, same orthographic plane).
#include "render/camera.h"

#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace vr {

static double radians(double deg) { return deg * std::numbers::pi / 180.0; }

// sin and cos of an angle in degrees, exact at multiples of 90 so that e.g. --azimuth 90 looks exactly along an
// axis (d_a == 0 on the other axes) instead of 6e-17 off it.
static void sinCosDeg(double deg, double& s, double& c) {
    const double r = std::fmod(deg, 360.0);
    const double quarter = r / 90.0;
    if (quarter == std::floor(quarter)) {
        constexpr double sines[] = {0, 1, 0, -1};
        const int q = (int(quarter) % 4 + 4) % 4;
        s = sines[q];
        c = sines[(q + 1) % 4];
        return;
    }
    s = std::sin(radians(r));
    c = std::cos(radians(r));
}

Camera Camera::fit(const GridGeometry& grid, const ViewParams& view) {
    if (view.width <= 0 || view.height <= 0)
        throw InputError("image size " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                         ": width and height must be positive");
    if (view.projection == Projection::Perspective && !(view.fovDeg > 0 && view.fovDeg < 180))
        throw InputError("--fov " + std::to_string(view.fovDeg) + ": the field of view must be in (0, 180) degrees");

    if (!std::isfinite(view.azimuthDeg) || !std::isfinite(view.elevationDeg))
        throw InputError("--azimuth / --elevation: the view angles must be finite numbers of degrees");

    Camera cam;
    cam.projection = view.projection;
    cam.width = view.width;
    cam.height = view.height;

    // Start on +z looking toward -z with +y up, then turn about up (azimuth, positive toward +x) and about
    // right (elevation, positive toward +y). Written in closed form so the frame stays exactly orthonormal.
    double sa, ca, se, ce;
    sinCosDeg(view.azimuthDeg, sa, ca);
    sinCosDeg(view.elevationDeg, se, ce);
    const Vec3d back{sa * ce, se, ca * ce};  // centre -> eye
    cam.forward = -back;
    cam.up = Vec3d{-sa * se, ce, -ca * se};
    cam.right = cross(cam.forward, cam.up);

    const Vec3d centre = grid.centre();
    const double radius = 0.5 * length(grid.extent());
    const double aspect = double(view.width) / double(view.height);
    if (view.projection == Projection::Orthographic) {
        // The bounding sphere fits the shorter image side.
        cam.halfHeight = aspect >= 1 ? radius : radius / aspect;
        // The plane sits outside the sphere; rays start on it (t_entry > 0 always).
        cam.eye = centre + back * (2 * radius);
    } else {
        cam.halfHeight = std::tan(radians(view.fovDeg) / 2);
        // Distance at which the sphere is tangent to the narrower of the two half-angles of the frustum.
        const double halfAngle = std::atan(cam.halfHeight * std::min(1.0, aspect));
        cam.eye = centre + back * (radius / std::sin(halfAngle));
    }
    return cam;
}

Ray Camera::ray(double px, double py) const {
    // Image-plane coordinates in [-1, 1]: (0,0) is the top-left corner, the image centre maps to (0,0).
    const double aspect = double(width) / double(height);
    const double u = (2 * px / width - 1) * halfHeight * aspect;
    const double v = (1 - 2 * py / height) * halfHeight;
    if (projection == Projection::Orthographic) return {eye + right * u + up * v, forward};
    return {eye, normalize(forward + right * u + up * v)};
}

}  // namespace vr
