#include "support/render_cases.h"

#include <cstdio>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>

#include "core/classified_volume.h"
#include "io/prepared_file.h"
#include "preprocess/classify/classify.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/hier_field.h"
#include "preprocess/segment/segment.h"
#include "render/cpu_renderer.h"
#include "support/datasets.h"

namespace vr::test {

const RenderFn kCpuReference = [](const PreparedVolume& p, const Camera& c, const RenderSettings& s) {
    return renderCpu(p, c, s);
};

namespace {

constexpr Caster kLeaping[] = {Caster::PC, Caster::ACD, Caster::EACD, Caster::Hier};

std::string casterText(Caster c) { return std::string(casterName(c)); }

// No NaN or Inf anywhere, opacity in [0, 1], colour not negative.
void expectSane(const RenderResult& r, const std::string& what) {
    std::size_t bad = 0;
    for (std::size_t i = 0; i < r.image.rgba.size(); ++i) {
        const float v = r.image.rgba[i];
        const bool alpha = i % 4 == 3;
        if (!std::isfinite(v) || v < 0 || (alpha && v > 1)) ++bad;
    }
    EXPECT_EQ(bad, 0u) << what << ": non-finite or out-of-range pixel values";
}

unsigned maxOf(const std::vector<uint32_t>& v) { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }

// Each caster's render, indexed by Caster.
using CasterRenders = std::array<RenderResult, int(Caster::Hier) + 1>;

// Renders the casters; every leaping caster must give the primitive image (thresholds are 0), represent the
// same samples and need no more fetches on any pixel.
CasterRenders renderAllAndCompare(const RenderFn& render, const PreparedVolume& p, const Camera& cam,
                                  RenderSettings s, const std::string& what, CaseCount& count) {
    CasterRenders out;
    for (Caster c : kCasters) {
        s.caster = c;
        out[int(c)] = render(p, cam, s);
        ++count.renders;
        count.rays += cam.width * cam.height;
        expectSane(out[int(c)], what + " " + casterText(c));
    }
    const RenderResult& prim = out[0];
    for (uint64_t n : prim.samples) count.hits += n > 0;
    for (Caster c : kLeaping) {
        const RenderResult& r = out[int(c)];
        EXPECT_LT(maxAbsDifference(prim.image, r.image), 1e-4) << what << " " << casterText(c);
        std::size_t moreFetches = 0, otherSamples = 0;
        for (std::size_t i = 0; i < r.iterations.size(); ++i) {
            moreFetches += r.iterations[i] > prim.iterations[i];
            otherSamples += r.samples[i] != prim.samples[i];
        }
        EXPECT_EQ(moreFetches, 0u) << what << " " << casterText(c) << ": pixels needing more fetches than primitive";
        // ert = 1 is the exception: primitive stops where A rounds to 1, a span where its samples end.
        if (s.ert < 1) {
            EXPECT_EQ(otherSamples, 0u) << what << " " << casterText(c) << ": pixels with other samples";
        }
    }
    return out;
}

RenderSettings unshaded(double stepVoxels, double ert) {
    RenderSettings s;
    s.shading = false;
    s.stepVoxels = stepVoxels;
    s.ert = ert;
    return s;
}

// Relative error, with an exact zero wanted exactly.
double relativeError(double got, double want) { return want == 0 ? std::abs(got) : std::abs(got - want) / want; }

// A 1 x 1 x M stack of slabs, voxel z of class slabs[z % 2], seen along z through the exact centre line
// (x = y = 0.5) from one voxel beyond either end. The entry is at t = 1 exactly.
struct SlabRay {
    int m;
    bool downward;  // -z
    Vec3d eye() const { return {0.5, 0.5, downward ? m + 1.0 : -1.0}; }
    Camera camera() const { return orthoCamera(eye(), {0, 0, downward ? -1.0 : 1.0}, {1, 0, 0}, 1, 1, 0.5); }
};

// Front-to-back over the lattice t_k = 1 + k dt < m + 1, each sample in voxel clamp(floor(z)), as docs/ALGORITHMS.md
// section 1 defines it, summed in long double from the stored (float) extinctions.
struct Composite {
    long double colour[3] = {0, 0, 0};
    long double alpha = 0;
    int64_t samples = 0;
};
Composite latticeSum(const SlabRay& ray, const PreparedVolume& p, double dt) {
    Composite c;
    const double oz = ray.eye().z, dz = ray.downward ? -1.0 : 1.0, tExit = ray.m + 1.0;
    for (int64_t k = 0;; ++k) {
        const double t = 1.0 + double(k) * dt;
        if (!(t < tExit)) break;
        const int z = std::clamp(int(std::floor(oz + dz * t)), 0, ray.m - 1);
        const std::size_t entry = std::size_t(p.scalars.values[std::size_t(z)]);
        const long double a = -std::expm1(-(long double)p.classification.table.sigma[entry] * dt);
        const long double w = (1 - c.alpha) * a;
        for (int ch = 0; ch < 3; ++ch) c.colour[ch] += w * p.classification.table.colour[entry][ch];
        c.alpha += w;
        ++c.samples;
    }
    return c;
}

}  // namespace

PreparedVolume syntheticPrepared(const GridGeometry& grid, double referenceStep,
                                 const std::function<VoxelClass(const Vec3i&)>& voxel) {
    PreparedVolume p;
    p.scalars.grid = grid;
    p.scalars.sourceType = ScalarType::UInt16;
    p.scalars.values.resize(grid.voxels());
    p.classification.referenceStep = referenceStep;
    TransferTable& table = p.classification.table;
    // Each distinct class an entry, in the order of first appearance; the voxel's scalar is its entry.
    std::map<std::array<float, 4>, std::size_t> entryOf;
    for (int z = 0; z < grid.dims.z; ++z)
        for (int y = 0; y < grid.dims.y; ++y)
            for (int x = 0; x < grid.dims.x; ++x) {
                const VoxelClass c = voxel({x, y, z});
                const std::array<float, 4> key{float(extinctionFromOpacity(c.alpha, referenceStep)),
                                               float(c.colour.x), float(c.colour.y), float(c.colour.z)};
                const auto [it, added] = entryOf.emplace(key, table.size());
                if (added) {
                    if (table.size() == 65536) throw std::invalid_argument("syntheticPrepared: over 65536 classes");
                    table.sigma.push_back(key[0]);
                    table.colour.push_back({key[1], key[2], key[3]});
                }
                p.scalars.values[linearIndex(grid.dims, x, y, z)] = float(it->second);
            }
    p.meta.segmentation = {0, 0, false, false};
    p.regions = segment(ClassifiedVoxels(p.scalars, p.classification, false), p.meta.segmentation);
    p.fields = buildFields(p.regions, kRegionFields);
    p.fields.hier = buildHierarchicalEACD(p, p.meta.segmentation);
    return p;
}

std::filesystem::path writtenSynthetic(const std::string& name, const GridGeometry& grid, double referenceStep,
                                       const std::function<VoxelClass(const Vec3i&)>& voxel) {
    const std::filesystem::path out = scratchDir(name) / (name + ".vprep");
    writePrepared(out, syntheticPrepared(grid, referenceStep, voxel));
    return out;
}

void expectNearCpuReference(const RenderResult& device, const RenderResult& cpu) {
    const std::size_t pixels = cpu.iterations.size();
    ASSERT_EQ(device.iterations.size(), pixels);
    std::size_t beyond = 0;
    double sum = 0, deviceIterations = 0, cpuIterations = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        double d = 0;
        for (std::size_t ch = 4 * i; ch < 4 * i + 4; ++ch)
            d = std::max(d, double(std::abs(device.image.rgba[ch] - cpu.image.rgba[ch])));
        sum += d;
        beyond += d > 1e-3;
        deviceIterations += device.iterations[i];
        cpuIterations += cpu.iterations[i];
    }
    EXPECT_LE(double(beyond), 0.005 * double(pixels)) << "pixels beyond 1e-3 of the CPU reference";
    EXPECT_LT(sum / double(pixels), 1e-4) << "mean difference from the CPU reference";
    EXPECT_NEAR(deviceIterations, cpuIterations, 0.01 * cpuIterations) << "iterations";
}

// Span opacity 1 - (1 - alpha)^N for per-sample opacity alpha and spans of N samples: one voxel seen along z from
// z = 2 at dt = 1 / N, the reference step being dt, so that the voxel is one span of N samples for ACD and EACD.
CaseCount spanOpacityGrid(const RenderFn& render, const CaseOptions& options) {
    CaseCount count;
    const GridGeometry grid{{1, 1, 1}, {1, 1, 1}, {0, 0, 0}};
    const Camera cam = orthoCamera({0.5, 0.5, 2}, {0, 0, -1}, {1, 0, 0}, 1, 1, 0.5);
    const Vec3d colour{0.25, 0.5, 1};
    for (const int64_t n : {int64_t(1), int64_t(10), int64_t(10000), int64_t(10000000)}) {
        const double dt = 1.0 / double(n);
        // The lattice 1 + k dt < 2 (entry and exit of the voxel), counted here in double.
        int64_t samples = std::max<int64_t>(0, n - 2);
        while (1.0 + double(samples) * dt < 2.0) ++samples;
        EXPECT_LE(std::abs(samples - n), 1);
        for (const double alpha : {0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.5, 1 - 1e-7, 1.0}) {
            const PreparedVolume p =
                syntheticPrepared(grid, dt, [&](const Vec3i&) { return VoxelClass{alpha, colour}; });
            const double want = alpha == 1 ? 1.0 : -std::expm1(double(samples) * std::log1p(-alpha));
            for (Caster c : kCasters) {
                const bool stepsEverySample = c == Caster::Primitive || c == Caster::PC;  // pc is 0 in one voxel
                if (stepsEverySample && samples > options.maxSteppedSamples) continue;
                RenderSettings s = unshaded(dt, 1.0);
                s.caster = c;
                // 1e7 samples across one voxel: the volume's diagonal would need more than the default cap allows.
                s.maxIterationsPerRay = std::max<long long>(s.maxIterationsPerRay, 2 * n);
                const RenderResult r = render(p, cam, s);
                ++count.renders;
                ++count.rays;
                ++count.hits;
                const std::string what = casterText(c) + " alpha " + std::to_string(alpha) + " N " + std::to_string(n);
                expectSane(r, what);
                const float got = r.image.pixel(0, 0)[3];
                if (alpha == 0) {
                    EXPECT_EQ(got, 0.0f) << what;
                } else if (alpha == 1) {
                    EXPECT_EQ(got, 1.0f) << what;
                } else {
                    EXPECT_LT(relativeError(got, want), 1e-4) << what << ": got " << got << ", want " << want;
                }
                for (int ch = 0; ch < 3; ++ch)
                    EXPECT_LT(relativeError(r.image.pixel(0, 0)[ch], colour[ch] * want), 1e-4)
                        << what << " channel " << ch;
                if (want < 0.5) {  // A cannot round to 1 early
                    EXPECT_LE(std::abs(int64_t(r.samples[0]) - samples), options.floatLattice ? 1 : 0) << what;
                }
                if (c == Caster::ACD || c == Caster::EACD) {  // the voxel's exit: T = 2
                    const int64_t slack = options.floatLattice ? int64_t(0x1p-18 * 2 / dt) : 0;
                    EXPECT_LE(r.iterations[0], 1 + slack) << what << ": one span";
                }
            }
        }
    }
    return count;
}

// Many thin regions: 1000 one-voxel slabs of two classes, both directions, steps from 1/64 voxel (faces hit
// exactly by the lattice) to 4 voxels (most slabs skipped), against the lattice sum in long double.
CaseCount thinSlabsAgainstTheLatticeSum(const RenderFn& render, const CaseOptions& options) {
    CaseCount count;
    const int m = 1000;
    const VoxelClass slabs[2] = {{0.002, {1, 0.2, 0}}, {1e-5, {0, 0.3, 1}}};
    const PreparedVolume p = syntheticPrepared({{1, 1, m}, {1, 1, 1}, {0, 0, 0}}, 1.0,
                                               [&](const Vec3i& v) { return slabs[v.z % 2]; });
    for (const bool downward : {true, false}) {
        const SlabRay ray{m, downward};
        for (const double dt : {1.0 / 64, 1.0 / 8, 0.25, 1.0 / 3, 0.5, 1.0, 1.5, 2.0, 4.0}) {
            const Composite want = latticeSum(ray, p, dt);
            EXPECT_GT(double(want.alpha), 0.3);  // deep enough to matter
            for (Caster c : kCasters) {
                // One-voxel regions: PC steps every sample too, and so does hier (every block is mixed).
                const bool steps = c == Caster::Primitive || c == Caster::PC || c == Caster::Hier;
                if (steps && want.samples > options.maxSteppedSamples) continue;
                RenderSettings s = unshaded(dt, 1.0);
                s.caster = c;
                const RenderResult r = render(p, ray.camera(), s);
                ++count.renders;
                ++count.rays;
                ++count.hits;
                const std::string what = casterText(c) + (downward ? " down" : " up") + " dt " + std::to_string(dt);
                expectSane(r, what);
                EXPECT_EQ(r.samples[0], uint64_t(want.samples)) << what;
                EXPECT_NEAR(r.image.pixel(0, 0)[3], double(want.alpha), 1e-5) << what;
                for (int ch = 0; ch < 3; ++ch)
                    EXPECT_NEAR(r.image.pixel(0, 0)[ch], double(want.colour[ch]), 1e-5) << what << " channel " << ch;
            }
        }
    }
    return count;
}

// One region of 4000 voxels along z, crossed along the edge shared by its four columns at dt = 1/64 (256,000
// samples): 1 - exp(-sigma L) exactly, for a tiny and a moderate opacity; EACD needs about 4000 / 255 spans.
CaseCount hugeRegionAgainstTheClosedForm(const RenderFn& render, const CaseOptions& options) {
    CaseCount count;
    const int m = 4000;
    const GridGeometry grid{{2, 2, m}, {1, 1, 1}, {0, 0, 0}};
    const Camera cam = orthoCamera({1, 1, m + 1.0}, {0, 0, -1}, {1, 0, 0}, 1, 1, 0.5);
    const Vec3d colour{0.5, 0.25, 1};
    const double dt = 1.0 / 64;
    for (const double alpha : {1e-9, 1e-4}) {
        const PreparedVolume p = syntheticPrepared(grid, 1.0, [&](const Vec3i&) { return VoxelClass{alpha, colour}; });
        const double want = -std::expm1(-double(p.classification.table.sigma[0]) * m);
        for (Caster c : kCasters) {
            // The ray runs along voxel edges, where the PC radius is 0: PC steps every sample too.
            if ((c == Caster::Primitive || c == Caster::PC) && int64_t(m) * 64 > options.maxSteppedSamples) continue;
            RenderSettings s = unshaded(dt, 1.0);
            s.caster = c;
            const RenderResult r = render(p, cam, s);
            ++count.renders;
            ++count.rays;
            ++count.hits;
            const std::string what = casterText(c) + " alpha " + std::to_string(alpha);
            expectSane(r, what);
            EXPECT_EQ(r.samples[0], uint64_t(m) * 64) << what;
            EXPECT_NEAR(r.image.pixel(0, 0)[3], want, 1e-5) << what;
            EXPECT_LT(relativeError(r.image.pixel(0, 0)[3], want), 1e-4) << what;
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(r.image.pixel(0, 0)[ch], colour[ch] * want, 1e-5) << what;
            if (c == Caster::EACD) {
                EXPECT_LE(r.iterations[0], uint32_t(std::ceil(m / 255.0)) + 2) << what;
            }
            if (c == Caster::Primitive) {
                EXPECT_EQ(r.iterations[0], uint32_t(m) * 64) << what;
            }
        }
    }
    return count;
}

// Opacity 1/2 per sample makes A = 1 - 2^-m land on ert = 1 - 2^-m: the leaping casters must stop at the very
// sample where primitive stepping does, inside one region and across one-voxel regions of two colours.
CaseCount earlyTerminationHitExactly(const RenderFn& render) {
    CaseCount count;
    for (const double dt : {0.25, 1.0 / 3}) {
        for (const bool striped : {false, true}) {
            const PreparedVolume p =
                syntheticPrepared({{1, 1, 64}, {1, 1, 1}, {0, 0, 0}}, dt, [&](const Vec3i& v) {
                    return VoxelClass{0.5, striped && v.z % 2 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0}};
                });
            const SlabRay ray{64, true};
            for (const double ert : {0.5, 0.75, 0.875, 0.9375, 0.96875, 0.99, 0.999}) {
                const std::string what = std::string(striped ? "stripes" : "one region") + " dt " +
                                         std::to_string(dt) + " ert " + std::to_string(ert);
                const auto r = renderAllAndCompare(render, p, ray.camera(), unshaded(dt, ert), what, count);
                // Stopped at the first sample reaching ert: one sample earlier would be below it.
                const double a = r[0].image.pixel(0, 0)[3];
                const int64_t m = int64_t(r[0].samples[0]);
                EXPECT_GE(a, ert - 1e-6) << what;
                EXPECT_LT(1 - std::pow(0.5, double(m - 1)), ert + 1e-12) << what;
                EXPECT_NEAR(a, 1 - std::pow(0.5, double(m)), 1e-6) << what;
            }
        }
    }
    return count;
}

namespace {

struct Shape {
    std::string name;
    Vec3i dims;
    Vec3d spacing{1, 1, 1};
};

std::vector<Shape> shapes() {
    return {{"1x1x1", {1, 1, 1}},
            {"1x1x9", {1, 1, 9}},
            {"9x1x1", {9, 1, 1}},
            {"1x7x1", {1, 7, 1}},
            {"2x2x2", {2, 2, 2}},
            {"7x11x13 (primes)", {7, 11, 13}},
            {"12x20x6", {12, 20, 6}},
            {"5x6x7 spacing 1:1:100", {5, 6, 7}, {1, 1, 100}},
            {"6x5x4 spacing 0.01:1:1", {6, 5, 4}, {0.01, 1, 1}},
            {"3x4x5 spacing 1:100:0.5", {3, 4, 5}, {1, 100, 0.5}}};
}

// A reproducible value in [0, 1) per voxel.
double hash01(const Vec3i& v, uint32_t salt) {
    uint32_t h = uint32_t(v.x) * 73856093u ^ uint32_t(v.y) * 19349663u ^ uint32_t(v.z) * 83492791u ^ salt;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return double(h % 100000) / 100000.0;
}

struct Content {
    std::string name;
    std::function<VoxelClass(const Vec3i&)> voxel;
};

std::vector<Content> contents() {
    return {{"constant", [](const Vec3i&) { return VoxelClass{0.3, {0.9, 0.6, 0.3}}; }},
            {"checkerboard",
             [](const Vec3i& v) {
                 return (v.x + v.y + v.z) % 2 ? VoxelClass{0.2, {1, 0, 0}} : VoxelClass{0.6, {0, 0, 1}};
             }},
            {"white noise",
             [](const Vec3i& v) {
                 const double a = hash01(v, 1);
                 // Opacity 0 and 1 voxels mixed into the noise.
                 return VoxelClass{a < 0.1 ? 0.0 : a > 0.9 ? 1.0 : a, {hash01(v, 2), hash01(v, 3), hash01(v, 4)}};
             }},
            {"all transparent", [](const Vec3i&) { return VoxelClass{0, {1, 1, 1}}; }},
            {"all opaque", [](const Vec3i&) { return VoxelClass{1, {0.2, 0.8, 0.4}}; }}};
}

ViewParams fitView(double az, double el, Projection proj = Projection::Orthographic) {
    return orbitView(az, el, 25, 19, proj);
}

struct NamedCamera {
    std::string name;
    Camera camera;
    double step;  // in voxels of the smallest spacing
};

// Views fitted to the volume: along each axis both ways, face and body diagonals, an oblique one, perspective.
std::vector<NamedCamera> fittedCameras(const GridGeometry& grid) {
    const double body = 35.264389682754654;
    const std::vector<std::pair<double, double>> angles{{0, 0},   {90, 0},  {180, 0},   {270, 0},     {0, 90},
                                                        {0, -90}, {45, 0},  {0, 45},    {135, -45},   {45, body},
                                                        {-135, -body}, {17, -63}};
    std::vector<NamedCamera> out;
    for (const auto& [az, el] : angles)
        out.push_back({"fit az " + std::to_string(az) + " el " + std::to_string(el),
                       Camera::fit(grid, fitView(az, el)), 0.37});
    out.push_back({"fit perspective az 30 el 20", Camera::fit(grid, fitView(30, 20, Projection::Perspective)), 0.5});
    out.push_back({"fit perspective az 0 el 0", Camera::fit(grid, fitView(0, 0, Projection::Perspective)), 1.0});
    return out;
}

// Rays from integer grid points: along an axis they run along voxel edges and their samples fall on faces (dt of
// 1 or 1/4 voxel); along a face diagonal they cross voxel edges, along a body diagonal voxel corners. The pixel
// grid is 1 voxel apart along `right` (an axis, so exactly) and up, and reaches one voxel beyond the volume on
// every side: rays graze faces and miss it too. Unit spacing only (grid = world).
std::vector<NamedCamera> latticeCameras(const Vec3i& dims) {
    struct Dir {
        Vec3i d;
        Vec3d right;
    };
    const std::vector<Dir> dirs{{{0, 0, -1}, {1, 0, 0}},  {{0, 0, 1}, {1, 0, 0}},  {{1, 0, 0}, {0, 0, 1}},
                                {{0, -1, 0}, {1, 0, 0}},  {{1, 1, 0}, {0, 0, 1}},  {{-1, 1, 0}, {0, 0, 1}},
                                {{1, 0, -1}, {0, 1, 0}},  {{0, -1, -1}, {1, 0, 0}},
                                {{1, 1, 1}, normalize(Vec3d{1, -1, 0})}, {{-1, 1, -1}, normalize(Vec3d{1, 1, 0})}};
    const int reach = std::max({dims.x, dims.y, dims.z}) + 2;
    const int size = 2 * reach + 1;
    const Vec3i centre{dims.x / 2, dims.y / 2, dims.z / 2};
    std::vector<NamedCamera> out;
    for (const Dir& dir : dirs) {
        const Vec3d eye = Vec3d(centre) - Vec3d(dir.d) * double(reach);
        const Vec3d forward = normalize(Vec3d(dir.d));
        const std::string name = "lattice dir " + std::to_string(dir.d.x) + "," + std::to_string(dir.d.y) + "," +
                                 std::to_string(dir.d.z);
        for (double step : {1.0, 0.25}) {
            out.push_back({name + " step " + std::to_string(step),
                           orthoCamera(eye, forward, dir.right, size, size, size / 2.0), step});
        }
    }
    return out;
}

// Perspective eyes inside the volume: at its centre, on a voxel corner (an integer grid point) and on the near
// corner of the grid, looking along an axis, a face diagonal and a body diagonal.
std::vector<NamedCamera> insideCameras(const GridGeometry& grid) {
    const Vec3d corner = grid.origin + Vec3d(Vec3i{grid.dims.x / 2, grid.dims.y / 2, grid.dims.z / 2}) * grid.spacing;
    std::vector<NamedCamera> out;
    for (const auto& [name, eye] : {std::pair<std::string, Vec3d>{"eye at the centre", grid.centre()},
                                    {"eye on a voxel corner", corner},
                                    {"eye on the grid's origin corner", grid.origin}}) {
        out.push_back({name + " looking -z", perspectiveCamera(eye, {0, 0, -1}, {1, 0, 0}, 15, 15, 90), 0.5});
        out.push_back({name + " looking along (1,1,0)",
                       perspectiveCamera(eye, normalize(Vec3d{1, 1, 0}), {0, 0, 1}, 15, 15, 100), 0.25});
        out.push_back({name + " looking along (1,1,1)",
                       perspectiveCamera(eye, normalize(Vec3d{1, 1, 1}), normalize(Vec3d{1, -1, 0}), 15, 15, 60), 1.0});
    }
    return out;
}

}  // namespace

CaseCount extremeGeometry(const RenderFn& render) {
    CaseCount count;
    for (const Shape& shape : shapes()) {
        const GridGeometry grid{shape.dims, shape.spacing, {0, 0, 0}};
        std::vector<NamedCamera> cameras = fittedCameras(grid);
        const std::vector<NamedCamera> inside = insideCameras(grid);
        cameras.insert(cameras.end(), inside.begin(), inside.end());
        if (shape.spacing == Vec3d{1, 1, 1}) {
            const std::vector<NamedCamera> lattice = latticeCameras(shape.dims);
            cameras.insert(cameras.end(), lattice.begin(), lattice.end());
        }
        for (const Content& content : contents()) {
            const PreparedVolume p = syntheticPrepared(grid, grid.smallestSpacing(), content.voxel);
            for (const NamedCamera& cam : cameras)
                for (const double ert : {0.99, 1.0}) {
                    const std::string what = shape.name + " " + content.name + " " + cam.name + " ert " +
                                             std::to_string(ert);
                    renderAllAndCompare(render, p, cam.camera, unshaded(cam.step, ert), what, count);
                }
        }
    }
    return count;
}

CaseCount transparentOpaqueAndCappedRegions(const RenderFn& render) {
    CaseCount count;
    const Vec3d background{0.1, 0.2, 0.3};
    // All transparent: the background exactly, no opacity; primitive fetches every sample, leaping the same
    // samples; rays that miss fetch nothing. All opaque: one fetch per ray that hits, alpha exactly 1.
    for (const Shape& shape : shapes()) {
        const GridGeometry grid{shape.dims, shape.spacing, {0, 0, 0}};
        const PreparedVolume clear = syntheticPrepared(grid, grid.smallestSpacing(), [](const Vec3i&) {
            return VoxelClass{0, {1, 1, 1}};
        });
        const PreparedVolume opaque = syntheticPrepared(grid, grid.smallestSpacing(), [](const Vec3i&) {
            return VoxelClass{1, {0.2, 0.8, 0.4}};
        });
        std::vector<NamedCamera> cameras = fittedCameras(grid);
        if (shape.spacing == Vec3d{1, 1, 1}) {
            const auto lattice = latticeCameras(shape.dims);
            cameras.insert(cameras.end(), lattice.begin(), lattice.end());
        }
        for (const NamedCamera& cam : cameras) {
            RenderSettings s = unshaded(cam.step, 0.99);
            s.background = background;
            const std::string what = shape.name + " " + cam.name;
            const auto c = renderAllAndCompare(render, clear, cam.camera, s, what + " transparent", count);
            std::size_t misses = 0;
            for (std::size_t i = 0; i < c[0].iterations.size(); ++i) {
                const float* px = &c[0].image.rgba[i * 4];
                EXPECT_TRUE(px[0] == float(background.x) && px[1] == float(background.y) &&
                            px[2] == float(background.z) && px[3] == 0.0f)
                    << what << " transparent pixel " << i;
                EXPECT_EQ(c[0].iterations[i], c[0].samples[i]) << what << " primitive pixel " << i;
                if (c[0].samples[i] == 0) {
                    ++misses;
                    for (Caster k : kLeaping) EXPECT_EQ(c[int(k)].iterations[i], 0u) << what << " missed pixel " << i;
                }
            }
            EXPECT_LT(misses, c[0].iterations.size()) << what << ": every ray missed";
            // One sample of the clamped opacity: 1 - 1e-12^(dt / dt0), which is 1.0f from dt = dt0 on.
            const double dt = cam.step * grid.smallestSpacing();
            const double first = -std::expm1(-double(opaque.classification.table.sigma[0]) * dt);
            const auto o = renderAllAndCompare(render, opaque, cam.camera, s, what + " opaque", count);
            for (Caster k : kCasters)
                for (std::size_t i = 0; i < o[0].iterations.size(); ++i) {
                    const RenderResult& r = o[int(k)];
                    const bool hit = c[0].samples[i] > 0;
                    EXPECT_EQ(r.iterations[i], hit ? 1u : 0u) << what << " opaque " << casterText(k) << " pixel " << i;
                    EXPECT_NEAR(r.image.rgba[i * 4 + 3], hit ? first : 0.0, 1e-7)
                        << what << " opaque " << casterText(k);
                    if (hit && cam.step >= 1) {
                        EXPECT_EQ(r.image.rgba[i * 4 + 3], 1.0f) << what << " opaque";
                    }
                }
        }
    }

    // Regions longer than the distance cap (255): a transparent 3 x 3 x 700 column and 1 x 1 x 700 line crossed
    // along their length, both ways, with samples on every voxel face (dt = 1/2). A box of edge e along the ray
    // moves the ray e voxels going up; going down the sample on a face lies in the voxel above it (floor), whose
    // box then holds only e - 1 voxels more. So EACD (z extent capped at 255) needs ceil(700 / 254) spans and a
    // couple more, ACD (cube edge e bounded by the lateral room of the ray's voxel) ceil(700 / e) + 1 going up and
    // ceil(700 / (e - 1)) + 1 going down, where an edge of 1 leaves one sample per fetch: primitive's 1400.
    for (const Vec3i dims : {Vec3i{3, 3, 700}, Vec3i{1, 1, 700}}) {
        const GridGeometry grid{dims, {1, 1, 1}, {0, 0, 0}};
        const PreparedVolume clear =
            syntheticPrepared(grid, 1.0, [](const Vec3i&) { return VoxelClass{0, {1, 1, 1}}; });
        for (const bool downward : {true, false})
            for (int x = 0; x < dims.x; ++x)
                for (int y = 0; y < dims.y; ++y) {
                    const Camera cam = orthoCamera({x + 0.5, y + 0.5, downward ? dims.z + 1.0 : -1.0},
                                                   {0, 0, downward ? -1.0 : 1.0}, {1, 0, 0}, 1, 1, 0.5);
                    const std::string what = "column " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                                             "x700 ray at " + std::to_string(x) + "," + std::to_string(y) +
                                             (downward ? " down" : " up");
                    const auto r = renderAllAndCompare(render, clear, cam, unshaded(0.5, 0.99), what, count);
                    EXPECT_EQ(r[0].iterations[0], 1400u) << what;
                    EXPECT_LE(r[int(Caster::EACD)].iterations[0], uint32_t(std::ceil(700.0 / 254)) + 2) << what;
                    const int edge = std::min({dims.x - x, dims.y - y, kDistanceCap}) - (downward ? 1 : 0);
                    const uint32_t acdBound = edge == 0 ? 1400u : uint32_t(std::ceil(700.0 / edge)) + 1;
                    EXPECT_LE(r[int(Caster::ACD)].iterations[0], acdBound) << what;
                    EXPECT_GE(r[int(Caster::ACD)].iterations[0] + 2, std::min(acdBound, 1400u)) << what << ": tight";
                }
    }
    return count;
}

// A ray that needs more fetches than the cap makes the render fail (an error, not a hang, not a silent image);
// exactly the fetches needed pass.
CaseCount iterationCapIsAnError(const RenderFn& render) {
    CaseCount count;
    const GridGeometry grid{{7, 11, 13}, {1, 1, 1}, {0, 0, 0}};
    for (const Content& content : contents()) {
        const PreparedVolume p = syntheticPrepared(grid, 1.0, content.voxel);
        const Camera cam = Camera::fit(grid, fitView(30, 20));
        for (Caster c : kCasters) {
            RenderSettings s = unshaded(0.5, 0.99);
            s.caster = c;
            const RenderResult first = render(p, cam, s);
            const unsigned needed = maxOf(first.iterations);
            ++count.renders;
            count.rays += cam.width * cam.height;
            for (uint64_t n : first.samples) count.hits += n > 0;
            const std::string what = content.name + " " + casterText(c) + " needing " + std::to_string(needed);
            EXPECT_GE(needed, 1u) << what;
            s.maxIterationsPerRay = needed;
            EXPECT_NO_THROW(render(p, cam, s)) << what;
            s.maxIterationsPerRay = needed - 1;
            if (needed > 1) {
                EXPECT_THROW(render(p, cam, s), std::runtime_error) << what;
            }
            count.renders += 2;
        }
    }
    return count;
}

void report(const char* family, const CaseCount& n) {
    std::printf("%s: %d renders, %d rays, %d of them hitting the volume\n", family, n.renders, n.rays, n.hits);
    EXPECT_GT(n.renders, 0) << family << ": no render";
    EXPECT_GT(n.rays, 0) << family << ": no ray cast";
    EXPECT_GT(n.hits, 0) << family << ": no ray sampled the volume";
}

}  // namespace vr::test
