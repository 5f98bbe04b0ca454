#include "datasets/phantoms.h"

#include <tbb/parallel_for.h>

#include <random>
#include <string>

#include "core/errors.h"

namespace vr {

namespace {

Volume emptyVolume(const std::string& name, Vec3i dims, Vec3d spacing, ScalarType type) {
    if (dims.x < 1 || dims.y < 1 || dims.z < 1) throw InputError("phantom " + name + ": dims must be positive");
    if (!(spacing.x > 0 && spacing.y > 0 && spacing.z > 0))
        throw InputError("phantom " + name + ": spacing must be positive");
    Volume v;
    v.grid.dims = dims;
    v.grid.spacing = spacing;
    v.sourceType = type;
    v.source = "phantom:" + name;
    v.values.resize(v.grid.voxels());
    return v;
}

// Fills every voxel from f(x, y, z), slices in parallel.
template <typename F>
Volume fill(const std::string& name, Vec3i dims, Vec3d spacing, ScalarType type, F f) {
    Volume v = emptyVolume(name, dims, spacing, type);
    tbb::parallel_for(0, dims.z, [&](int z) {
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) v.values[linearIndex(dims, x, y, z)] = f(x, y, z);
    });
    return v;
}

}  // namespace

Volume constantPhantom(Vec3i dims, float value, Vec3d spacing) {
    return fill("constant", dims, spacing, ScalarType::Float32, [&](int, int, int) { return value; });
}

Volume rampPhantom(Vec3i dims, int axis, float from, float to, Vec3d spacing) {
    if (axis < 0 || axis > 2) throw InputError("phantom ramp: axis must be 0, 1 or 2");
    int last = dims[axis] - 1;
    return fill("ramp", dims, spacing, ScalarType::Float32, [&](int x, int y, int z) {
        Vec3i v(x, y, z);
        return last == 0 ? from : from + (to - from) * float(v[axis]) / float(last);
    });
}

Volume shellsPhantom(Vec3i dims, Vec3d spacing) {
    constexpr float air = -1000, softTissue = 40, bone = 1000, brain = 30;
    Vec3d extent = Vec3d(dims) * spacing;
    Vec3d centre = extent * 0.5;
    double radius = 0.5 * minComponent(extent);
    return fill("shells", dims, spacing, ScalarType::Int16, [&](int x, int y, int z) {
        Vec3d p = (Vec3d(Vec3i(x, y, z)) + Vec3d(0.5, 0.5, 0.5)) * spacing;
        double r = length(p - centre) / radius;
        if (r > 0.9) return air;
        if (r > 0.8) return softTissue;
        if (r > 0.65) return bone;
        return brain;
    });
}

Volume checkerboardPhantom(Vec3i dims, float low, float high, Vec3d spacing) {
    return fill("checkerboard", dims, spacing, ScalarType::Float32,
                [&](int x, int y, int z) { return (x + y + z) % 2 ? high : low; });
}

Volume noisePhantom(Vec3i dims, uint32_t seed, int low, int high, Vec3d spacing) {
    if (low > high) throw InputError("phantom noise: low must not exceed high");
    // One generator in voxel order: the same seed gives the same volume whatever the thread count.
    Volume v = emptyVolume("noise", dims, spacing, ScalarType::UInt8);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> value(low, high);
    for (float& f : v.values) f = float(value(rng));
    return v;
}

Volume enginePhantom(Vec3i dims, Vec3d spacing) {
    constexpr float air = 0, casting = 200, rib = 255;
    return fill("engine", dims, spacing, ScalarType::UInt8, [&](int x, int y, int z) {
        // Fractions of the grid, so that the part keeps its shape at any size.
        double u = (x + 0.5) / dims.x, v = (y + 0.5) / dims.y, w = (z + 0.5) / dims.z;
        bool inBlock = u > 0.15 && u < 0.85 && v > 0.2 && v < 0.8 && w > 0.1 && w < 0.9;
        double du = u - 0.5, dv = v - 0.5;
        bool inBore = du * du + dv * dv < 0.15 * 0.15;
        bool onRib = u > 0.05 && u < 0.95 && v > 0.3 && v < 0.7 && w > 0.1 && w < 0.9 && int(w * 8) % 2 == 0 &&
                     w * 8 - int(w * 8) < 0.3;
        if (inBore) return air;
        if (onRib) return rib;
        return inBlock ? casting : air;
    });
}

}  // namespace vr
