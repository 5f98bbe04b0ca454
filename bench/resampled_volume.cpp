#include "resampled_volume.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace vr::bench {
namespace {

// Source position of destination voxel i when n voxels are resampled to m over the same extent (centres aligned).
struct Tap {
    int lo, hi;
    double w;  // weight of hi
};
std::vector<Tap> taps(int n, int m) {
    std::vector<Tap> t(m);
    for (int i = 0; i < m; ++i) {
        const double s = std::clamp((i + 0.5) * n / m - 0.5, 0.0, double(n - 1));
        const int lo = int(s);
        t[i] = {lo, std::min(lo + 1, n - 1), s - lo};
    }
    return t;
}

// The range a type holds; float's is unbounded.
std::pair<double, double> typeRange(ScalarType t) {
    switch (t) {
        case ScalarType::UInt8: return {0, 255};
        case ScalarType::Int16: return {-32768, 32767};
        case ScalarType::UInt16: return {0, 65535};
        default: return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    }
}

}  // namespace

Volume resample(const Volume& v, Vec3i dims) {
    Volume out;
    out.grid = v.grid;
    out.grid.dims = dims;
    for (int a = 0; a < 3; ++a) out.grid.spacing[a] = v.grid.spacing[a] * v.grid.dims[a] / dims[a];
    out.sourceType = v.sourceType;
    out.source = v.source + " resampled";
    out.values.resize(out.grid.voxels());
    const std::vector<Tap> tx = taps(v.grid.dims.x, dims.x), ty = taps(v.grid.dims.y, dims.y),
                           tz = taps(v.grid.dims.z, dims.z);
    const bool integer = v.sourceType != ScalarType::Float32;
    tbb::parallel_for(tbb::blocked_range<int>(0, dims.z), [&](const tbb::blocked_range<int>& zs) {
        for (int z = zs.begin(); z != zs.end(); ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const Tap &a = tx[x], &b = ty[y], &c = tz[z];
                    const auto line = [&](int j, int k) {
                        return v.at(a.lo, j, k) * (1 - a.w) + v.at(a.hi, j, k) * a.w;
                    };
                    const auto plane = [&](int k) { return line(b.lo, k) * (1 - b.w) + line(b.hi, k) * b.w; };
                    const double f = plane(c.lo) * (1 - c.w) + plane(c.hi) * c.w;
                    out.values[linearIndex(dims, x, y, z)] = float(integer ? std::round(f) : f);
                }
    });
    return out;
}

Volume withNoise(Volume v, double sigma, unsigned seed) {
    const std::pair<double, double> range = typeRange(v.sourceType);  // not a structured binding: clang 14's lambdas
    const double lo = range.first, hi = range.second;                   // cannot capture one
    const bool integer = v.sourceType != ScalarType::Float32;
    const std::size_t slice = std::size_t(v.grid.dims.x) * std::size_t(v.grid.dims.y);
    tbb::parallel_for(tbb::blocked_range<int>(0, v.grid.dims.z), [&](const tbb::blocked_range<int>& zs) {
        for (int z = zs.begin(); z != zs.end(); ++z) {
            std::mt19937 rng(seed * 7919u + unsigned(z));
            std::normal_distribution<double> noise(0, sigma);
            float* values = v.values.data() + std::size_t(z) * slice;
            for (std::size_t i = 0; i < slice; ++i) {
                const double f = std::clamp(double(values[i]) + noise(rng), lo, hi);
                values[i] = float(integer ? std::round(f) : f);
            }
        }
    });
    v.source += " with noise";
    return v;
}

}  // namespace vr::bench
