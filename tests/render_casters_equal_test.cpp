// The first correctness test of every caster (docs/ALGORITHMS.md section 5): with T_o = T_a = 0, nearest and
// trilinear sampling and view-independent shading (headlight), PC, ACD, EACD and hier render the primitive caster's
// image, on every real dataset and on phantoms, at axis-aligned, diagonal and perspective views; and they need
// fewer fetches.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <numeric>

#include "datasets/phantoms.h"
#include "render/cpu_renderer.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/volumes.h"
#include "support/views.h"

namespace vr {
namespace {

constexpr double kTolerance = 1e-6;

PreparedVolume prepare(const Volume& volume, const TransferFunction& tf, bool normals, bool trilinear = false) {
    return test::prepareVolume(volume, tf, {0, 0, normals, trilinear});
}

ViewParams view(Projection p, double az, double el, int size) { return test::orbitView(az, el, size, size, p); }

// Exactly axis-aligned along -z, -x and +y, two diagonals in different octants, and a perspective view.
std::vector<ViewParams> views(int size) {
    return {view(Projection::Orthographic, 0, 0, size),    view(Projection::Orthographic, 90, 0, size),
            view(Projection::Orthographic, 0, -90, size),  view(Projection::Orthographic, 37, 23, size),
            view(Projection::Orthographic, -130, -50, size), view(Projection::Perspective, 25, 35, size)};
}

double meanOf(const std::vector<uint32_t>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

// Mean iterations per ray, indexed by Caster.
using MeanIterations = std::array<double, int(Caster::Hier) + 1>;

// Renders every caster and compares with the primitive one; returns the mean iterations per caster.
MeanIterations expectCastersEqual(const PreparedVolume& p, const ViewParams& v, RenderSettings settings,
                                         const std::string& what) {
    const Camera camera = Camera::fit(p.grid(), v);
    const std::string where = what + " view az " + std::to_string(v.azimuthDeg) + " el " +
                              std::to_string(v.elevationDeg) +
                              (v.projection == Projection::Perspective ? " perspective" : " ortho");
    settings.caster = Caster::Primitive;
    const RenderResult primitive = renderCpu(p, camera, settings);
    MeanIterations mean{meanOf(primitive.iterations)};
    const uint64_t primitiveSamples = std::accumulate(primitive.samples.begin(), primitive.samples.end(), uint64_t(0));
    for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD, Caster::Hier}) {
        settings.caster = c;
        const RenderResult r = renderCpu(p, camera, settings);
        EXPECT_LT(maxAbsDifference(primitive.image, r.image), kTolerance) << casterName(c) << " on " << where;
        // Each fetch stands for >= 1 of the same samples, so no pixel needs more fetches than primitive's.
        std::size_t worse = 0;
        for (std::size_t i = 0; i < r.iterations.size(); ++i) worse += r.iterations[i] > primitive.iterations[i];
        EXPECT_EQ(worse, 0u) << casterName(c) << " on " << where;
        const uint64_t samples = std::accumulate(r.samples.begin(), r.samples.end(), uint64_t(0));
        // Spans stop where primitive stepping reaches ert; with ert = 1 primitive stops where A rounds to 1.
        if (settings.ert < 1) {
            EXPECT_NEAR(double(samples), double(primitiveSamples), 1e-4 * double(primitiveSamples))
                << casterName(c) << " on " << where;
        }
        mean[int(c)] = meanOf(r.iterations);
    }
    return mean;
}

// Mean fetches per ray over all views: ACD and EACD take no more than PC, EACD no more than ACD (with a
// little slack: paths differ once the leaps differ); hier no more than primitive.
void expectFewerIterations(const MeanIterations& mean, const std::string& what) {
    std::cout << what << ": mean iterations per ray primitive " << mean[0] << ", pc " << mean[1] << ", acd "
              << mean[2] << ", eacd " << mean[3] << ", hier " << mean[int(Caster::Hier)] << "\n";
    EXPECT_LE(mean[1], mean[0]) << what;
    EXPECT_LE(mean[2], 1.05 * mean[1]) << what;
    EXPECT_LE(mean[3], 1.02 * mean[2]) << what;
    EXPECT_LE(mean[int(Caster::Hier)], mean[0]) << what;
}

MeanIterations sum(MeanIterations a, const MeanIterations& b) {
    for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
    return a;
}

using test::datasetTransferFunction;

// The central block of at most `edge` voxels per axis, at full resolution: the large volumes are sampled so that
// building their distance fields stays quick. VR_FULL_DATASETS=1 renders them whole (about 20 s each in fields).
Volume centralBlock(const Volume& v, int edge) {
    return std::getenv("VR_FULL_DATASETS") ? v : test::centralBlock(v, edge);
}

TEST(RenderCastersEqual, EveryRealDataset) {
    const auto rows = test::rawManifest();
    ASSERT_GE(rows.size(), 9u);
    RenderSettings settings;
    settings.stepVoxels = 1.0;  // small images at step 1 keep the big volumes quick
    for (const auto& row : rows) {
        const Volume volume = centralBlock(test::loadDataset(row), 96);
        const PreparedVolume p = prepare(volume, datasetTransferFunction(row.tf), true);
        MeanIterations total{};
        for (const ViewParams& v : views(48)) total = sum(total, expectCastersEqual(p, v, settings, row.file));
        expectFewerIterations(total, row.file);
    }
}

// As users render: trilinear (post-classified) and shaded, on the regions volprep makes for it.
TEST(RenderCastersEqual, EveryRealDatasetTrilinear) {
    RenderSettings settings;
    settings.stepVoxels = 1.0;
    settings.trilinear = true;
    for (const auto& row : test::rawManifest()) {
        const Volume volume = centralBlock(test::loadDataset(row), 64);
        const PreparedVolume p = prepare(volume, datasetTransferFunction(row.tf), true, true);
        for (const ViewParams& v : views(32)) expectCastersEqual(p, v, settings, row.file + " trilinear");
    }
}

struct Phantom {
    std::string name;
    Volume volume;
    std::string tf;
};

std::vector<Phantom> phantoms() {
    return {{"shells", shellsPhantom({40, 36, 24}, {1, 1, 2}), "cranium_ct.tf.json"},
            {"ramp", rampPhantom({32, 30, 28}, 1), "mri.tf.json"},
            {"checkerboard", checkerboardPhantom({17, 16, 15}, 60, 240), "mri.tf.json"},
            {"noise", noisePhantom({24, 25, 26}, 7), "mri.tf.json"},
            {"engine", enginePhantom({48, 40, 36}, {0.8, 0.8, 1.2}), "mri.tf.json"},
            {"constant", constantPhantom({20, 20, 20}, 200), "mri.tf.json"}};
}

TEST(RenderCastersEqual, PhantomsWithShadingStepsAndErt) {
    for (const Phantom& ph : phantoms()) {
        const PreparedVolume shaded = prepare(ph.volume, datasetTransferFunction(ph.tf), true);
        const PreparedVolume unshaded = prepare(ph.volume, datasetTransferFunction(ph.tf), false);
        MeanIterations total{};
        // dt smaller than, not dividing, and larger than a voxel; without early termination too.
        for (double step : {0.37, 1.0, 2.5})
            for (const ViewParams& v : views(40)) {
                RenderSettings s;
                s.stepVoxels = step;
                const std::string what = ph.name + " step " + std::to_string(step);
                total = sum(total, expectCastersEqual(shaded, v, s, what + " shaded"));
                // A fixed directional light: the shade is still constant along each ray.
                s.lightDirection = Vec3d{1, 2, 3};
                expectCastersEqual(shaded, v, s, what + " lit from (1,2,3)");
                s.lightDirection.reset();
                s.shading = false;
                s.ert = 1.0;
                s.background = {0.2, 0.3, 0.4};
                expectCastersEqual(unshaded, v, s, what + " unshaded, no ert");
            }
        expectFewerIterations(total, ph.name);
    }
}

TEST(RenderCastersEqual, PhantomsTrilinear) {
    // Border voxels of the 2x2x2 footprint are regions of their own, so a leap never crosses interpolation
    // between regions: with thresholds 0 leaping is exact with trilinear sampling too.
    for (const Phantom& ph : phantoms()) {
        const PreparedVolume p = prepare(ph.volume, datasetTransferFunction(ph.tf), true, true);
        RenderSettings s;
        s.trilinear = true;
        s.stepVoxels = 0.5;
        for (const ViewParams& v : views(32)) expectCastersEqual(p, v, s, ph.name + " trilinear");
    }
}

}  // namespace
}  // namespace vr
