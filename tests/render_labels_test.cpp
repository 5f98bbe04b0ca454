// Label maps beside the scalars in the CPU reference (docs/ALGORITHMS.md section 2, label maps): each label shows in
// its own colour and opacity together with the transfer function, is never interpolated across another, shades by
// its smoothed indicator, and the regions never hold two labels, so that the leaping casters still render the
// primitive caster's image at thresholds 0.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/classify.h"
#include "preprocess/classify/label_colours.h"
#include "preprocess/segment/classified_voxels.h"
#include "render/cpu_renderer.h"
#include "support/label_maps.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/views.h"
#include "support/volumes.h"

namespace vr {
namespace {

// A CT block and its labels: soft tissue (1) and bone (2), thresholded as a segmentation would give them.
struct Labelled {
    Volume volume;
    TransferFunction tf;
    LabelMap labels;
};

Labelled headCt() {
    const test::DatasetEntry row = test::rawDataset("vtk_headsq_ct");
    Labelled l{test::centralBlock(test::loadDataset(row), 40), test::datasetTransferFunction(row.tf), {}};
    l.labels = test::thresholdLabels(l.volume, {1000, 2200});
    return l;
}

PreparedVolume prepare(const Labelled& l, bool trilinear, double to = 0, double ta = 0) {
    return test::prepareVolume(l.volume, l.tf, {to, ta, true, trilinear}, kRegionFields, l.labels);
}

TEST(RenderLabels, LeapingCastersEqualPrimitiveAtThresholdsZero) {
    const Labelled l = headCt();
    for (bool trilinear : {false, true}) {
        const PreparedVolume p = prepare(l, trilinear);
        for (const ViewParams& v : {test::orbitView(0, 0, 40, 40), test::orbitView(37, 23, 40, 40),
                                    test::orbitView(-130, -50, 40, 40, Projection::Perspective)}) {
            const Camera camera = Camera::fit(p.grid(), v);
            RenderSettings s = test::renderSettings(Caster::Primitive, true, trilinear);
            const RenderResult primitive = renderCpu(p, camera, s);
            for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD}) {
                s.caster = c;
                const RenderResult r = renderCpu(p, camera, s);
                EXPECT_LT(maxAbsDifference(primitive.image, r.image), 1e-6)
                    << casterName(c) << (trilinear ? " trilinear" : " nearest") << " az " << v.azimuthDeg;
            }
        }
    }
}

TEST(RenderLabels, RegionsNeverHoldTwoLabels) {
    const Labelled l = headCt();
    for (bool trilinear : {false, true})
        for (double to : {0.0, 0.1}) {
            const PreparedVolume p = prepare(l, trilinear, to, 10);
            std::vector<int> labelOf(p.regions.count, -1);
            std::size_t mixed = 0;
            for (std::size_t i = 0; i < p.regions.label.size(); ++i) {
                int& first = labelOf[p.regions.label[i]];
                if (first < 0) first = p.labels->label[i];
                mixed += first != p.labels->label[i];
            }
            EXPECT_EQ(mixed, 0u) << (trilinear ? "trilinear" : "nearest") << " T_o " << to;
        }
}

// A clear volume (the transfer function shows nothing) with a cube of label 1 in opaque red: a ray through the cube
// shows red, one beside it the background; with trilinear sampling too, whose scalars the label never blends.
TEST(RenderLabels, ALabelShowsItsOwnColourAndOpacity) {
    const Volume v = test::volumeOf({20, 20, 20}, {1, 1, 1}, ScalarType::UInt8, [](int, int, int) { return 10.0; });
    const TransferFunction clear = parseTransferFunction(
        R"({"Points": [0, 0, 0.5, 0, 255, 0, 0.5, 0], "RGBPoints": [0, 1, 1, 1, 255, 1, 1, 1]})", "clear");
    LabelMap labels;
    labels.label.assign(v.values.size(), 0);
    for (int z = 6; z < 14; ++z)
        for (int y = 6; y < 14; ++y)
            for (int x = 6; x < 14; ++x) labels.label[linearIndex(v.grid.dims, x, y, z)] = 1;
    labels.rgba = {{0, 0, 0, 0}, {255, 0, 0, 255}};
    for (bool trilinear : {false, true}) {
        const PreparedVolume p = test::prepareVolume(v, clear, {0, 0, true, trilinear}, kRegionFields, labels);
        const Camera camera = Camera::fit(p.grid(), test::orbitView(0, 0, 21, 21));
        RenderSettings s = test::renderSettings(Caster::Primitive, false, trilinear);
        s.background = {0, 0, 1};
        const RenderResult r = renderCpu(p, camera, s);
        const float* centre = r.image.pixel(10, 10);
        EXPECT_NEAR(centre[0], 1, 1e-5);
        EXPECT_NEAR(centre[2], 0, 1e-5);
        const float* corner = r.image.pixel(1, 1);
        EXPECT_NEAR(corner[2], 1, 1e-6);
        EXPECT_NEAR(corner[3], 0, 1e-6);
        // Without the label map the same volume shows nothing.
        PreparedVolume unlabelled = p;
        unlabelled.labels.reset();
        EXPECT_NEAR(renderCpu(unlabelled, camera, s).image.pixel(10, 10)[3], 0, 1e-12);
    }
}

// The combination: extinctions add, colours mix by extinction, each side exactly where the other adds nothing.
TEST(RenderLabels, LabelsMixWithTheTransferFunction) {
    EXPECT_EQ(device::labelledSigma(2.0, 3.0), 5.0);
    EXPECT_EQ(device::labelledChannel(2.0, 0.25, 0.0, 1.0), 0.25);
    EXPECT_EQ(device::labelledChannel(0.0, 0.25, 3.0, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(device::labelledChannel(1.0, 0.0, 3.0, 1.0), 0.75);
}

// A ball of label 1: its surface voxels shade by normals within a few degrees of the ball's radius, where the
// staircase of its voxels (the plain central difference of the indicator) is off by far more.
TEST(RenderLabels, SurfacesShadeByTheSmoothedIndicator) {
    const Vec3i dims{33, 33, 33};
    const Volume v = test::volumeOf(dims, {1, 1, 1}, ScalarType::UInt8, [](int, int, int) { return 0.0; });
    LabelMap labels;
    labels.label.resize(v.values.size());
    const Vec3d centre{16.5, 16.5, 16.5};
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                labels.label[linearIndex(dims, x, y, z)] = length(Vec3d{x + 0.5, y + 0.5, z + 0.5} - centre) < 11;
    labels.rgba = {{0, 0, 0, 0}, {200, 200, 200, 255}};
    labels.classes = classifyLabels(labels.rgba, 1);
    const ScalarClassification c =
        scalarClassification(v, ClassifyParams{test::datasetTransferFunction("mri.tf.json")});
    const ClassifiedVoxels voxels(v, c, true, &labels);
    double smoothed = 0, staircase = 0;
    int surface = 0;
    for (int z = 1; z + 1 < dims.z; ++z)
        for (int y = 1; y + 1 < dims.y; ++y)
            for (int x = 1; x + 1 < dims.x; ++x) {
                const std::size_t i = linearIndex(dims, x, y, z);
                if (labels.label[i] != 1) continue;
                Vec3d plain;
                for (int a = 0; a < 3; ++a) {
                    Vec3i lo{x, y, z}, hi{x, y, z};
                    --lo[a];
                    ++hi[a];
                    plain[a] = double(labels.label[linearIndex(dims, hi.x, hi.y, hi.z)]) -
                               labels.label[linearIndex(dims, lo.x, lo.y, lo.z)];
                }
                if (length(plain) == 0) continue;  // inside: no surface here
                const std::array<float, 3> n = voxels.normal(i);
                const Vec3d inward = normalize(centre - Vec3d{x + 0.5, y + 0.5, z + 0.5});
                const auto angle = [&](const Vec3d& u) { return std::acos(std::clamp(dot(u, inward), -1.0, 1.0)); };
                smoothed += angle(Vec3d{n[0], n[1], n[2]});
                staircase += angle(normalize(plain));
                ++surface;
            }
    ASSERT_GT(surface, 100);
    const double degrees = 180 / std::numbers::pi;
    EXPECT_LT(smoothed / surface * degrees, 8.0);
    EXPECT_LT(smoothed, 0.6 * staircase);
}

TEST(RenderLabels, OtherBlendsAreRefusedNamingBoth) {
    const Labelled l = headCt();
    const PreparedVolume p = prepare(l, false);
    RenderSettings s = test::renderSettings(Caster::Blocks, false);
    s.blend = Blend::MIP;
    try {
        renderCpu(p, Camera::fit(p.grid(), test::orbitView(0, 0, 8, 8)), s);
        ADD_FAILURE() << "rendered a label map with --blend mip";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--labels with --blend mip"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vr
