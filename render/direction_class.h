// Classes of ray directions by the signs of their components, as the ray probe behind --caster auto counts them
// (render/caster_choice.h). A direction with a zero component leaps
// differently from its neighbours: an ACD or EACD box never ends on that axis's faces, so an axis-aligned or
// in-plane orthographic view takes other iterations than the octant around it. Each sign is -1, 0 or +1: the 26
// classes are the 8 octants, the 12 quadrants of the coordinate planes and the 6 axis directions.
#pragma once
#include "core/distance_fields.h"
#include "render/camera.h"
#include "render/view_octants.h"
#include "shaders/device_contract.h"

namespace vr {

// Class index (sx + 1) + 3 (sy + 1) + 9 (sz + 1); index 13 (all signs 0) is no direction.
constexpr int kDirectionClasses = 27;
constexpr int kNoDirection = 13;

constexpr int directionClass(int sx, int sy, int sz) { return (sx + 1) + 3 * (sy + 1) + 9 * (sz + 1); }
// Sign of axis a (-1, 0, +1) of class c.
constexpr int classSign(int c, int axis) { return (axis == 0 ? c : axis == 1 ? c / 3 : c / 9) % 3 - 1; }
constexpr int octantClass(int oct) {
    return directionClass(device::octantSign(oct, 0), device::octantSign(oct, 1), device::octantSign(oct, 2));
}
inline int directionClassOf(const Vec3d& d) {
    auto sign = [](double x) { return (x > 0) - (x < 0); };
    return directionClass(sign(d.x), sign(d.y), sign(d.z));
}

// Bit c set for each class the probe's counts for a view are taken from: an orthographic view's one direction;
// a perspective view's rays lie in general position, so the classes of its octants (viewOctants).
inline unsigned viewDirectionClasses(const Camera& camera) {
    if (camera.projection == Projection::Orthographic) return 1u << directionClassOf(camera.forward);
    unsigned classes = 0;
    const unsigned octants = viewOctants(camera);
    for (int oct = 0; oct < kOctants; ++oct)
        if (octants >> oct & 1) classes |= 1u << octantClass(oct);
    return classes;
}

}  // namespace vr
