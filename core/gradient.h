// The scalar gradient: classification and shading read it the same way (docs/ALGORITHMS.md section 2).
#pragma once
#include <array>

#include "vec3.h"
#include "volume.h"

namespace vr {

// Central differences in physical units (divided by 2h), one-sided at the border (divided by h);
// an axis with a single voxel has no derivative (0). One voxel at a time: the definition that classify's row-wise
// gradients are tested against, bit for bit.
inline Vec3d centralGradient(const Volume& volume, int x, int y, int z) {
    const Vec3i& n = volume.grid.dims;
    const Vec3i v{x, y, z};
    Vec3d g;
    for (int a = 0; a < 3; ++a) {
        if (n[a] < 2) continue;
        Vec3i lo = v, hi = v;
        lo[a] = std::max(v[a] - 1, 0);
        hi[a] = std::min(v[a] + 1, n[a] - 1);
        const double span = (hi[a] - lo[a]) * volume.grid.spacing[a];
        g[a] = (double(volume.at(hi.x, hi.y, hi.z)) - double(volume.at(lo.x, lo.y, lo.z))) / span;
    }
    return g;
}

// The unit normal of gradient g, in float, or (0,0,0) where |g| is at most `flat` (no direction to shade by).
inline std::array<float, 3> unitNormal(const Vec3d& g, double flat) {
    const double magnitude = length(g);
    if (!(magnitude > flat)) return {0, 0, 0};
    return {float(g.x / magnitude), float(g.y / magnitude), float(g.z / magnitude)};
}

}  // namespace vr
