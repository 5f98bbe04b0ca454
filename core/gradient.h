// The scalar gradient: classification and shading read it the same way (docs/ALGORITHMS.md section 2).
#pragma once
#include <algorithm>
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

// centralGradient of the voxels x0 .. x0 + count - 1 of row (y, z), into gx, gy and gz (count each): the same
// operations in the same order, bit for bit, a run at a time (along y and z the difference of two whole rows).
inline void centralGradientRun(const Volume& volume, int x0, int count, int y, int z, double* gx, double* gy,
                               double* gz) {
    const Vec3i& n = volume.grid.dims;
    const Vec3d& h = volume.grid.spacing;
    const float* row = &volume.values[linearIndex(n, 0, y, z)];
    for (int i = 0; i < count; ++i) {
        const int x = x0 + i, lo = std::max(x - 1, 0), hi = std::min(x + 1, n.x - 1);
        gx[i] = n.x < 2 ? 0 : (double(row[hi]) - double(row[lo])) / ((hi - lo) * h.x);
    }
    // Along y or z (axis length `length`, this row at v): rowAt(w) is the row at w on that axis.
    const auto alongRows = [&](double* g, int length, int v, double spacing, auto rowAt) {
        if (length < 2) {
            std::fill(g, g + count, 0.0);
            return;
        }
        const int lo = std::max(v - 1, 0), hi = std::min(v + 1, length - 1);
        const double span = (hi - lo) * spacing;
        const float *a = rowAt(lo) + x0, *b = rowAt(hi) + x0;
        for (int i = 0; i < count; ++i) g[i] = (double(b[i]) - double(a[i])) / span;
    };
    alongRows(gy, n.y, y, h.y, [&](int w) { return &volume.values[linearIndex(n, 0, w, z)]; });
    alongRows(gz, n.z, z, h.z, [&](int w) { return &volume.values[linearIndex(n, 0, y, w)]; });
}

// The unit normal of gradient g, in float, or (0,0,0) where |g| is at most `flat` (no direction to shade by).
inline std::array<float, 3> unitNormal(const Vec3d& g, double flat) {
    const double magnitude = length(g);
    if (!(magnitude > flat)) return {0, 0, 0};
    return {float(g.x / magnitude), float(g.y / magnitude), float(g.z / magnitude)};
}

}  // namespace vr
