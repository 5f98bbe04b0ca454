// Coded EACD (core/extent_code.h) on the CPU reference: a box rounded down is still homogeneous, so at thresholds 0
// the EACD caster still renders the primitive caster's image with each code, on phantoms and real datasets, in
// nearest and trilinear sampling; the coarser the code, the more fetches (reported, with a loose bound).
#include <gtest/gtest.h>

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

constexpr ExtentCode kCodes[] = {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8};

PreparedVolume prepare(const Volume& volume, const std::string& tf, bool trilinear) {
    return test::prepareVolume(volume, test::datasetTransferFunction(tf), {0, 0, true, trilinear}, kFieldEACD);
}

ViewParams view(Projection p, double az, double el, int size) { return test::orbitView(az, el, size, size, p); }

double meanOf(const std::vector<uint32_t>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

// Renders EACD with every code against primitive; returns the mean iterations per ray of each code.
std::array<double, 3> expectEveryCodeEqualsPrimitive(const PreparedVolume& exact, RenderSettings s,
                                                     const std::string& what) {
    std::array<double, 3> mean{};
    for (const ViewParams& v : {view(Projection::Orthographic, 0, 0, 40), view(Projection::Orthographic, 37, 23, 40),
                                view(Projection::Orthographic, -130, -50, 40),
                                view(Projection::Perspective, 25, 35, 40)}) {
        const Camera camera = Camera::fit(exact.grid(), v);
        s.caster = Caster::Primitive;
        const RenderResult primitive = renderCpu(exact, camera, s);
        s.caster = Caster::EACD;
        for (ExtentCode code : kCodes) {
            PreparedVolume p = exact;
            quantiseEACD(p.fields, code);
            const RenderResult r = renderCpu(p, camera, s);
            const std::string where =
                what + " " + std::string(extentCodeName(code)) + " az " + std::to_string(v.azimuthDeg);
            EXPECT_LT(maxAbsDifference(primitive.image, r.image), 1e-6) << where;
            std::size_t worse = 0;
            for (std::size_t i = 0; i < r.iterations.size(); ++i) worse += r.iterations[i] > primitive.iterations[i];
            EXPECT_EQ(worse, 0u) << where;
            mean[int(code)] += meanOf(r.iterations);
        }
    }
    std::cout << what << ": mean iterations per ray, EACD exact " << mean[0] / 4 << ", log16 " << mean[1] / 4
              << ", joint8 " << mean[2] / 4 << "\n";
    // Smaller boxes cannot save fetches overall; the paths differ once the leaps differ, hence the slack.
    EXPECT_LE(mean[0], 1.02 * mean[1]) << what;
    EXPECT_LE(mean[1], 1.02 * mean[2]) << what;
    return mean;
}

TEST(RenderExtentCode, EveryCodeRendersThePrimitiveImageOnPhantoms) {
    struct Phantom {
        std::string name;
        Volume volume;
        std::string tf;
    };
    for (const Phantom& ph :
         std::vector<Phantom>{{"shells", shellsPhantom({40, 36, 24}, {1, 1, 2}), "cranium_ct.tf.json"},
                              {"engine", enginePhantom({48, 40, 36}, {0.8, 0.8, 1.2}), "mri.tf.json"},
                              {"ramp", rampPhantom({32, 30, 28}, 1), "mri.tf.json"},
                              {"noise", noisePhantom({24, 25, 26}, 7), "mri.tf.json"}}) {
        for (bool trilinear : {false, true}) {
            RenderSettings s;
            s.trilinear = trilinear;
            s.stepVoxels = 0.37;
            expectEveryCodeEqualsPrimitive(prepare(ph.volume, ph.tf, trilinear), s,
                                           ph.name + (trilinear ? " trilinear" : " nearest"));
        }
    }
}

TEST(RenderExtentCode, EveryCodeRendersThePrimitiveImageOnRealDatasets) {
    for (const char* prefix : {"boston_teapot", "cranium_ct"}) {
        const test::DatasetEntry row = test::rawDataset(prefix);
        const Volume volume = test::centralBlock(test::loadDataset(row), 96);
        RenderSettings s;
        s.stepVoxels = 0.5;
        expectEveryCodeEqualsPrimitive(prepare(volume, row.tf, false), s, row.file);
    }
}

}  // namespace
}  // namespace vr
