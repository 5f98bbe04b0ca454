#include "preprocess/pipeline/ray_probe.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include "volrender/cpu_renderer.h"

namespace vr {
using json = nlohmann::json;

namespace {

constexpr int kViewsPerOctant = 16, kViewPixels = 4;  // 16 views of 4 x 4 rays: 256 rays per octant
// Samples across the volume at half the default step above which rays are too long to probe (2^17: at most
// 2^28 iterations per caster; real volumes of 512^3 take about 3500).
constexpr double kMaxProbeSamples = 0x1p17;
constexpr std::array<Caster, 4> kProbed{Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD};

bool hasField(const DistanceFields& f, Caster c) {
    return c == Caster::Primitive || (c == Caster::PC && f.hasPC()) || (c == Caster::ACD && f.hasACD()) ||
           (c == Caster::EACD && f.hasEACD());
}

// View `j` of octant `oct`: a direction from a Kronecker sequence (the plastic number's R2), uniform in the
// cosine of its angle to the xz plane and in azimuth, so uniform over the octant's solid angle; as the view
// angles of Camera::fit (forward = -(sin az cos el, sin el, cos az cos el)).
ViewParams probeView(int oct, int j) {
    const double y = std::fmod(0.5 + j * 0.7548776662466927, 1.0);
    const double phi = std::fmod(0.5 + j * 0.5698402909980532, 1.0) * std::numbers::pi / 2;
    const double xz = std::sqrt(1 - y * y);
    const Vec3d d{octantSign(oct, 0) * xz * std::sin(phi), octantSign(oct, 1) * y,
                  octantSign(oct, 2) * xz * std::cos(phi)};
    ViewParams v;
    v.width = v.height = kViewPixels;
    v.azimuthDeg = std::atan2(-d.x, -d.z) * 180 / std::numbers::pi;
    v.elevationDeg = std::asin(-d.y) * 180 / std::numbers::pi;
    return v;
}

// Mean iterations per pixel of caster c over octant oct's views at a step.
double meanIterations(const PreparedVolume& p, Caster c, int oct, double stepVoxels) {
    RenderSettings s;
    s.caster = c;
    s.stepVoxels = stepVoxels;
    s.shading = false;
    std::array<double, kViewsPerOctant> perView{};
    tbb::parallel_for(0, kViewsPerOctant, [&](int j) {
        const RenderResult r = renderCpu(p, Camera::fit(p.classified.grid, probeView(oct, j)), s);
        perView[j] = std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0);
    });
    return std::accumulate(perView.begin(), perView.end(), 0.0) / (kViewsPerOctant * kViewPixels * kViewPixels);
}

}  // namespace

json rayProbe(const PreparedVolume& p) {
    const RenderSettings defaults;
    const GridGeometry& grid = p.classified.grid;
    if (length(grid.extent()) / (defaults.stepVoxels / 2 * grid.smallestSpacing()) > kMaxProbeSamples) return json();
    json probe{{"stepVoxels", defaults.stepVoxels}, {"ert", defaults.ert}, {"views", kViewsPerOctant}};
    for (const Caster caster : kProbed) {
        if (!hasField(p.fields, caster)) continue;
        json leaps = json::array(), singles = json::array();
        for (int oct = 0; oct < kOctants; ++oct) {
            // At the default step I = L + S, at half of it L + 2 S: single samples double, leaps stay. The
            // primitive caster takes single samples only.
            const double atStep = meanIterations(p, caster, oct, defaults.stepVoxels);
            const double atHalf = caster == Caster::Primitive ? 2 * atStep
                                                              : meanIterations(p, caster, oct, defaults.stepVoxels / 2);
            const double single = std::clamp(atHalf - atStep, 0.0, atStep);
            leaps.push_back(atStep - single);
            singles.push_back(single);
        }
        probe["casters"][std::string(casterName(caster))] = {{"leaps", leaps}, {"singleSamples", singles}};
    }
    return probe;
}

}  // namespace vr
