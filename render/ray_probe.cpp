#include "render/caster_choice.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "render/cpu_renderer.h"
#include "render/direction_class.h"

namespace vr {

static_assert(kProbeDirectionClasses == kDirectionClasses, "the probe counts every direction class");

namespace {

// Views of 4 x 4 rays per class: more for the octants (every perspective view and most orthographic ones draw on
// them, and their directions spread over a solid angle) than for a plane's quadrant or an axis.
constexpr int kViewPixels = 4;
constexpr int kOctantViews = 16, kQuadrantViews = 6, kAxisViews = 8;
// Samples across the volume at half the default step above which rays are too long to probe (2^17: at most
// 2^28 iterations per caster; real volumes of 512^3 take about 3500).
constexpr double kMaxProbeSamples = 0x1p17;

// The leaping casters, whether a volume has their field, and where the probe keeps their counts.
struct LeapingCaster {
    Caster caster;
    bool (DistanceFields::*has)() const;
    std::optional<ProbeCounts> RayProbe::*counts;
};
constexpr LeapingCaster kLeaping[] = {{Caster::PC, &DistanceFields::hasPC, &RayProbe::pc},
                                      {Caster::ACD, &DistanceFields::hasACD, &RayProbe::acd},
                                      {Caster::EACD, &DistanceFields::hasEACD, &RayProbe::eacd}};

double fraction(double x) { return x - std::floor(x); }

// Radical inverse of j in base b: the Halton sequence.
double radicalInverse(int j, int b) {
    double r = 0, f = 1.0 / b;
    for (; j > 0; j /= b, f /= b) r += f * (j % b);
    return r;
}

struct ProbeView {
    int directionClass;
    Vec3d direction;  // unit, its zero components exactly 0
    double jitterX, jitterY;  // offset of the pixel lattice, in pixels: [-0.5, 0.5)
};

// View `j` of class c. Octants: directions from a Kronecker sequence (the plastic number's R2), uniform in the
// cosine of their angle to the xz plane and in azimuth, so uniform over the octant's solid angle. Quadrants:
// uniform in angle. Each view's 4 x 4 pixel lattice is shifted by a Halton offset, so that the views together
// sample the image plane finely (one unshifted 4 x 4 lattice misses the centre, where rays are longest).
ProbeView probeView(int c, int j) {
    const Vec3i s{classSign(c, 0), classSign(c, 1), classSign(c, 2)};
    const int zeros = (s.x == 0) + (s.y == 0) + (s.z == 0);
    Vec3d d{double(s.x), double(s.y), double(s.z)};
    if (zeros == 0) {
        const double y = fraction(0.5 + j * 0.7548776662466927);
        const double phi = fraction(0.5 + j * 0.5698402909980532) * std::numbers::pi / 2;
        const double xz = std::sqrt(1 - y * y);
        d = Vec3d{s.x * xz * std::sin(phi), s.y * y, s.z * xz * std::cos(phi)};
    } else if (zeros == 1) {
        const double phi = fraction(0.5 + j * 0.6180339887498949) * std::numbers::pi / 2;
        const int a = s.x == 0 ? 1 : 0, b = s.z == 0 ? 1 : 2;  // the two nonzero axes
        d = Vec3d{0, 0, 0};
        d[a] = s[a] * std::cos(phi);
        d[b] = s[b] * std::sin(phi);
    }
    return {c, d, radicalInverse(j + 1, 2) - 0.5, radicalInverse(j + 1, 3) - 0.5};
}

// An orthographic camera of kViewPixels^2 rays looking along the view's direction at the whole volume (the
// bounding sphere fits the image, as Camera::fit), its pixel lattice shifted by the view's jitter.
Camera probeCamera(const GridGeometry& grid, const ProbeView& v) {
    ViewParams fitted;
    fitted.width = fitted.height = kViewPixels;
    Camera cam = Camera::fit(grid, fitted);
    cam.forward = v.direction;
    // Any up perpendicular to the direction: the mean over the image does not depend on the roll.
    const Vec3d axis = std::abs(v.direction.y) < 0.9 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0};
    cam.up = normalize(axis - v.direction * dot(axis, v.direction));
    cam.right = cross(cam.forward, cam.up);
    const double pixel = 2 * cam.halfHeight / kViewPixels;
    cam.eye = grid.centre() - v.direction * length(grid.extent()) + cam.right * (v.jitterX * pixel) +
              cam.up * (v.jitterY * pixel);
    return cam;
}

std::vector<ProbeView> probeViews() {
    std::vector<ProbeView> views;
    for (int c = 0; c < kDirectionClasses; ++c) {
        if (c == kNoDirection) continue;
        const int zeros = (classSign(c, 0) == 0) + (classSign(c, 1) == 0) + (classSign(c, 2) == 0);
        const int count = zeros == 0 ? kOctantViews : zeros == 1 ? kQuadrantViews : kAxisViews;
        for (int j = 0; j < count; ++j) views.push_back(probeView(c, j));
    }
    return views;
}

// Per direction class (class kNoDirection: 0), the mean per pixel of caster c's loop iterations and of the
// lattice samples they stood for.
struct ClassMeans {
    PerDirectionClass iterations{}, samples{};
};

ClassMeans meanIterations(const PreparedVolume& p, const std::vector<ProbeView>& views, Caster c,
                          double stepVoxels) {
    RenderSettings s;
    s.caster = c;
    s.stepVoxels = stepVoxels;
    s.shading = false;
    std::vector<std::array<double, 2>> perView(views.size());
    tbb::parallel_for(std::size_t(0), views.size(), [&](std::size_t i) {
        const RenderResult r = renderCpu(p, probeCamera(p.grid(), views[i]), s);
        perView[i] = {std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0),
                      std::accumulate(r.samples.begin(), r.samples.end(), 0.0)};
    });
    ClassMeans m;
    PerDirectionClass rays{};
    for (std::size_t i = 0; i < views.size(); ++i) {
        const auto c = std::size_t(views[i].directionClass);
        m.iterations[c] += perView[i][0];
        m.samples[c] += perView[i][1];
        rays[c] += kViewPixels * kViewPixels;
    }
    for (std::size_t c = 0; c < rays.size(); ++c) {
        m.iterations[c] /= std::max(rays[c], 1.0);
        m.samples[c] /= std::max(rays[c], 1.0);
    }
    return m;
}

}  // namespace

std::optional<RayProbe> probeRays(const PreparedVolume& p) {
    const RenderSettings defaults;
    const GridGeometry& grid = p.grid();
    if (length(grid.extent()) / (defaults.stepVoxels / 2 * grid.smallestSpacing()) > kMaxProbeSamples)
        return std::nullopt;
    const std::vector<ProbeView> views = probeViews();
    RayProbe probe;
    probe.stepVoxels = defaults.stepVoxels;
    probe.ert = defaults.ert;
    probe.octantViews = kOctantViews;
    probe.quadrantViews = kQuadrantViews;
    probe.axisViews = kAxisViews;
    // The primitive caster takes one iteration per lattice sample a leaping caster's iterations stand for (the
    // same until termination at thresholds 0, and close to it above): no need to run it, its rays being the
    // longest. Only a volume without fields, where auto has nothing to choose, probes it.
    std::optional<PerDirectionClass> primitive;
    for (const LeapingCaster& leaping : kLeaping) {
        if (!(p.fields.*leaping.has)()) continue;
        // At the default step I = L + S, at half of it L + 2 S: single samples double, leaps stay.
        const ClassMeans atStep = meanIterations(p, views, leaping.caster, defaults.stepVoxels);
        const ClassMeans atHalf = meanIterations(p, views, leaping.caster, defaults.stepVoxels / 2);
        ProbeCounts& counts = (probe.*leaping.counts).emplace();
        for (std::size_t c = 0; c < counts.leaps.size(); ++c) {
            const double iterations = atStep.iterations[c];
            counts.singleSamples[c] = std::clamp(atHalf.iterations[c] - iterations, 0.0, iterations);
            counts.leaps[c] = iterations - counts.singleSamples[c];
        }
        if (!primitive) primitive = atStep.samples;
    }
    probe.primitive.singleSamples =
        primitive ? *primitive : meanIterations(p, views, Caster::Primitive, defaults.stepVoxels).iterations;
    return probe;
}

double probeIterations(const PreparedVolume& prepared, const std::vector<Camera>& cameras,
                       const RenderSettings& settings) {
    constexpr int kSide = 16;
    RenderSettings probe = settings;
    probe.shading = false;
    double sum = 0;
    for (Camera camera : cameras) {  // the same frustum at fewer pixels
        const int longer = std::max(camera.width, camera.height);
        camera.width = std::max(1, camera.width * kSide / longer);
        camera.height = std::max(1, camera.height * kSide / longer);
        const RenderResult r = renderCpu(prepared, camera, probe);
        sum += std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0) / double(r.iterations.size());
    }
    return cameras.empty() ? 0 : sum / double(cameras.size());
}

}  // namespace vr
