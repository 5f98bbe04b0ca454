#include "render/view_octants.h"

#include <cmath>
#include <vector>

#include "core/distance_fields.h"
#include "shaders/device_contract.h"

namespace vr {

unsigned viewOctants(const Camera& camera) {
    if (camera.projection == Projection::Orthographic)
        return 1u << device::octantOf(camera.forward.x, camera.forward.y, camera.forward.z);

    // Unnormalised direction forward + right u + up v over the image rectangle |u| <= uMax, |v| <= vMax.
    const double vMax = camera.halfHeight;
    const double uMax = vMax * double(camera.width) / double(camera.height);
    auto direction = [&](double u, double v) { return camera.forward + camera.right * u + camera.up * v; };

    std::vector<std::pair<double, double>> points{{-uMax, -vMax}, {uMax, -vMax}, {-uMax, vMax}, {uMax, vMax}};
    for (int a = 0; a < 3; ++a) {
        // Zero line of component a: f + r u + p v = 0, crossed with the four edges.
        const double f = camera.forward[a], r = camera.right[a], p = camera.up[a];
        for (double v : {-vMax, vMax})
            if (r != 0) points.emplace_back(-(f + p * v) / r, v);
        for (double u : {-uMax, uMax})
            if (p != 0) points.emplace_back(u, -(f + r * u) / p);
        for (int b = a + 1; b < 3; ++b) {
            const double f2 = camera.forward[b], r2 = camera.right[b], p2 = camera.up[b];
            const double det = r * p2 - p * r2;
            if (det != 0) points.emplace_back((p * f2 - f * p2) / det, (f * r2 - r * f2) / det);
        }
    }

    const double eps = 1e-9;  // components are O(1): forward, right and up are unit vectors
    unsigned mask = 0;
    for (auto [u, v] : points) {
        if (std::abs(u) > uMax * (1 + eps) + eps || std::abs(v) > vMax * (1 + eps) + eps) continue;
        const Vec3d d = direction(u, v);
        for (int oct = 0; oct < kOctants; ++oct) {
            bool possible = true;
            for (int a = 0; a < 3 && possible; ++a)
                possible = std::abs(d[a]) <= eps || (d[a] < 0) == (device::octantSign(oct, a) < 0);
            if (possible) mask |= 1u << oct;
        }
    }
    return mask;
}

}  // namespace vr
