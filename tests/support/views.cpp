#include "support/views.h"

#include <cmath>
#include <numbers>

namespace vr::test {

ViewParams orbitView(double azimuthDeg, double elevationDeg, int width, int height, Projection projection,
                     double fovDeg) {
    ViewParams v;
    v.projection = projection;
    v.azimuthDeg = azimuthDeg;
    v.elevationDeg = elevationDeg;
    v.fovDeg = fovDeg;
    v.width = width;
    v.height = height;
    return v;
}

RenderSettings renderSettings(Caster caster, bool shading, bool trilinear) {
    RenderSettings s;
    s.caster = caster;
    s.shading = shading;
    s.trilinear = trilinear;
    return s;
}

Camera orthoCamera(const Vec3d& eye, const Vec3d& forward, const Vec3d& right, int width, int height,
                   double halfHeight) {
    Camera c;
    c.projection = Projection::Orthographic;
    c.width = width;
    c.height = height;
    c.eye = eye;
    c.forward = forward;
    c.right = right;
    c.up = cross(right, forward);  // so that right == cross(forward, up)
    c.halfHeight = halfHeight;
    return c;
}

Camera perspectiveCamera(const Vec3d& eye, const Vec3d& forward, const Vec3d& right, int width, int height,
                         double fovDeg) {
    Camera c = orthoCamera(eye, forward, right, width, height, std::tan(fovDeg * std::numbers::pi / 360));
    c.projection = Projection::Perspective;
    return c;
}

}  // namespace vr::test
