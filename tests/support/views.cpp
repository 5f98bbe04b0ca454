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

std::vector<Clipping> clippings(const GridGeometry& grid) {
    const Vec3d c = grid.centre(), e = grid.extent();
    // A plane through point p with normal n keeps dot(n, x) >= dot(n, p).
    auto through = [](const Vec3d& p, const Vec3d& n) { return ClipPlane{n, dot(n, p)}; };
    const ClipPlane oblique = through(c, {1, 0.6, -0.3});
    const ClipPlane wedge = through(c + Vec3d{0, 0.2 * e.y, 0}, {-0.4, -1, 0.5});
    const Vec3i n = grid.dims;
    const CropBox crop{{n.x / 5, n.y / 4, 1}, {n.x - 3, 3 * n.y / 4, n.z / 2}};
    std::vector<ClipPlane> six;  // a slab on each axis, tilted: the box they leave is not the grid's
    for (int a = 0; a < 3; ++a) {
        Vec3d axis{0, 0, 0};
        axis[a] = 1;
        axis[(a + 1) % 3] = 0.25;
        six.push_back(through(c - axis * (0.3 * e[a]), axis));
        six.push_back(through(c + axis * (0.3 * e[a]), axis * -1.0));
    }
    return {{"one oblique plane", {oblique}, std::nullopt},
            {"a wedge of two planes", {oblique, wedge}, std::nullopt},
            {"a crop box", {}, crop},
            {"a crop box and a plane", {wedge}, crop},
            {"six planes", six, std::nullopt}};
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
