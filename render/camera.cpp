// The camera convention of docs/ALGORITHMS.md section 1. The casters take this class's eye, axes and half height,
// and map pixels to the image plane with the same function (shaders/ray_math.h), so they cast the same rays.
#include "render/camera.h"

#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.h"
#include "core/number_text.h"
#include "shaders/ray_math.h"

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

// v turned by deg about the unit axis k, right-handed (Rodrigues); exact at multiples of 90 about an axis.
static Vec3d turned(const Vec3d& v, const Vec3d& k, double deg) {
    double s, c;
    sinCosDeg(deg, s, c);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

static std::string vectorText(const Vec3d& v) {
    return numberText(v.x) + "," + numberText(v.y) + "," + numberText(v.z);
}

// --up: made orthogonal to the view direction (VTK's OrthogonalizeViewUp); refused when it has no such part.
static Vec3d orthogonalUp(const Vec3d& up, const Vec3d& forward) {
    const double norm = length(up);
    if (!(norm > 0) || !std::isfinite(norm))
        throw InputError("--up " + vectorText(up) + ": the up vector must be a non-zero finite direction");
    const Vec3d across = up / norm - forward * dot(up / norm, forward);
    if (length(across) < kMinUpSine)
        throw InputError("--up " + vectorText(up) + " is parallel to the view direction " + vectorText(forward) +
                         ": it cannot say which way is up (turn the view with --azimuth / --elevation, or choose "
                         "another up)");
    return normalize(across);
}

// The camera's frame before it is placed: the direction from the focal point to the eye, and up.
struct Frame {
    Vec3d back, up;
};

// Start on +z looking toward -z with +y up, then turn about up (azimuth, positive toward +x) and about right
// (elevation, positive toward +y). Written in closed form so the frame stays exactly orthonormal. The orbit's turn
// about +y is a change of azimuth; about another view-up it turns the eye about that vector.
static Frame viewFrame(const ViewParams& view) {
    double sa, ca, se, ce;
    sinCosDeg(view.up ? view.azimuthDeg : view.azimuthDeg + view.orbitDeg, sa, ca);
    sinCosDeg(view.elevationDeg, se, ce);
    Frame frame{{sa * ce, se, ca * ce}, {-sa * se, ce, -ca * se}};
    if (view.up) {
        frame.back = turned(frame.back, normalize(*view.up), view.orbitDeg);
        frame.up = orthogonalUp(*view.up, -frame.back);
    }
    return frame;
}

void checkView(const ViewParams& view) {
    if (view.width <= 0 || view.height <= 0)
        throw InputError("image size " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                         ": width and height must be positive");
    if (view.projection == Projection::Perspective && !(view.fovDeg > 0 && view.fovDeg < 180))
        throw InputError("--fov " + numberText(view.fovDeg) + ": the field of view must be in (0, 180) degrees");
    if (!std::isfinite(view.azimuthDeg) || !std::isfinite(view.elevationDeg) || !std::isfinite(view.orbitDeg))
        throw InputError("--azimuth / --elevation: the view angles must be finite numbers of degrees");
    if (!(view.zoom >= kMinZoom && view.zoom <= kMaxZoom))
        throw InputError("--zoom " + numberText(view.zoom) + ": the zoom factor must be in [" + numberText(kMinZoom) +
                         ", " + numberText(kMaxZoom) + "]");
    if (view.projection == Projection::Perspective && !(view.fovDeg / view.zoom < 180))
        throw InputError("--zoom " + numberText(view.zoom) + " with --fov " + numberText(view.fovDeg) +
                         ": the zoomed field of view fov / zoom must stay below 180 degrees");
    viewFrame(view);  // refuses an up along the view direction, whatever the orbit's turn about it
}

Camera Camera::fit(const GridGeometry& grid, const ViewParams& view) {
    checkView(view);
    Camera cam;
    cam.projection = view.projection;
    cam.width = view.width;
    cam.height = view.height;
    const Frame frame = viewFrame(view);
    const Vec3d back = frame.back;  // centre -> eye
    cam.forward = -back;
    cam.up = frame.up;
    cam.right = cross(cam.forward, cam.up);

    const Vec3d volumeCentre = grid.centre();
    const double radius = 0.5 * length(grid.extent());
    const Vec3d centre = view.centre.value_or(volumeCentre);
    const double offCentre = length(centre - volumeCentre);
    if (!(offCentre <= kMaxCentreRadii * radius))
        throw InputError("--center " + vectorText(centre) + ": farther than " + numberText(kMaxCentreRadii) +
                         " bounding radii (" + numberText(radius) + " each) from the volume centre " +
                         vectorText(volumeCentre));
    const double aspect = double(view.width) / double(view.height);
    if (view.projection == Projection::Orthographic) {
        // The bounding sphere fits the shorter image side.
        cam.halfHeight = (aspect >= 1 ? radius : radius / aspect) / view.zoom;
        // The plane sits outside the sphere, however far the focal point is from it; rays start on it
        // (t_entry > 0 always).
        cam.eye = centre + back * (2 * radius + offCentre);
    } else {
        // Distance at which the sphere is tangent to the narrower of the two half-angles of the unzoomed frustum;
        // zoom then narrows the view angle, as VTK's Zoom does, without moving the eye.
        const double halfAngle = std::atan(std::tan(radians(view.fovDeg) / 2) * std::min(1.0, aspect));
        cam.eye = centre + back * (radius / std::sin(halfAngle));
        cam.halfHeight = std::tan(radians(view.fovDeg / view.zoom) / 2);
    }
    return cam;
}

std::vector<Camera> Camera::orbit(const GridGeometry& grid, const ViewParams& view, int views) {
    std::vector<Camera> cameras;
    for (int i = 0; i < views; ++i) {
        ViewParams v = view;
        v.orbitDeg = view.orbitDeg + 360.0 * i / views;
        cameras.push_back(fit(grid, v));
    }
    return cameras;
}

Ray Camera::ray(double px, double py) const {
    const double u = device::imagePlaneU(px, width, height, halfHeight) + shift;
    const double v = device::imagePlaneV(py, height, halfHeight);
    if (projection == Projection::Orthographic) return {eye + right * u + up * v, forward};
    return {eye, normalize(forward + right * u + up * v)};
}

}  // namespace vr
