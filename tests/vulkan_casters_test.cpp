// The Vulkan casters against the CPU reference, against each other at thresholds 0, and their stiff cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <set>
#include <stdexcept>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/transfer_function.h"
#include "render/cpu_renderer.h"
#include "render/view_octants.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/volumes.h"
#include "support/vulkan.h"

namespace vr {
namespace {

using test::expectNoValidationErrors;
using test::kCasters;
using test::renderSettings;

// 40-pixel tiles on 64x48 images: full and partial tiles in both directions.
VulkanRenderer& renderer() { return test::vulkanRenderer(40); }

// Covers HU phantoms and datasets (-1000..3000) and 8-bit ones (0..255); opacity 1 at the top (the stiff case).
const TransferFunction& phantomTf() {
    static const TransferFunction tf = parseTransferFunction(R"({
        "Points": [-1000, 0, 0.5, 0, -100, 0, 0.5, 0, 0, 0.02, 0.5, 0, 40, 0.1, 0.5, 0, 100, 0.05, 0.5, 0,
                   200, 0.3, 0.5, 0, 255, 0.6, 0.5, 0, 1000, 0.9, 0.5, 0, 3000, 1, 0.5, 0],
        "RGBPoints": [-1000, 0.2, 0.1, 0.1, 0, 0.9, 0.5, 0.4, 128, 0.3, 0.8, 0.2, 255, 1, 1, 0.9, 3000, 1, 1, 1]
    })", "phantom TF");
    return tf;
}

PreparedVolume prepare(const Volume& volume, const TransferFunction& tf, double to, double ta, bool trilinear = false) {
    return test::prepareVolume(volume, tf, {to, ta, true, trilinear});
}

struct Dataset {
    std::string name;
    Volume volume;
    TransferFunction tf;
};

// A shared dataset's centred block of at most `edge` voxels per axis: the large real volumes are sampled, not
// rendered whole.
Dataset loadDataset(const test::DatasetEntry& e, int edge) {
    return {e.file, test::centralBlock(test::loadDataset(e), edge), test::datasetTransferFunction(e.tf)};
}

Dataset loadDataset(const std::string& prefix, int edge) { return loadDataset(test::rawDataset(prefix), edge); }

std::vector<Dataset> phantoms() {
    return {{"constant", constantPhantom({24, 20, 28}, 150), phantomTf()},
            {"ramp", rampPhantom({32, 24, 20}, 0, 0, 255, {1, 1, 2}), phantomTf()},
            {"shells", shellsPhantom({36, 36, 30}, {1, 1, 1.5}), phantomTf()},
            {"checkerboard", checkerboardPhantom({16, 16, 16}), phantomTf()},
            {"noise", noisePhantom({24, 24, 24}, 7), phantomTf()},
            {"engine", enginePhantom({40, 32, 24}), phantomTf()}};
}

ViewParams view(double az, double el, Projection projection = Projection::Orthographic) {
    return test::orbitView(az, el, 64, 48, projection);
}

double meanIterations(const RenderResult& r) {
    return std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0) / double(r.iterations.size());
}

// Every caster on the device matches the double-precision CPU reference, leaping with thresholds > 0.
void expectMatchesCpu(const std::string& name, const PreparedVolume& p, bool trilinear) {
    const std::vector<ViewParams> views{view(0, 0), view(37, 23), view(-120, -35),
                                        view(30, -20, Projection::Perspective)};
    for (const ViewParams& vp : views) {
        const Camera cam = Camera::fit(p.grid(), vp);
        for (Caster c : kCasters) {
            const RenderSettings s = renderSettings(c, true, trilinear);
            const RenderResult gpu = renderer().render(p, cam, s);
            const RenderResult cpu = renderCpu(p, cam, s);
            SCOPED_TRACE(name + " " + std::string(casterName(c)) + " az " + std::to_string(vp.azimuthDeg) +
                         (vp.projection == Projection::Perspective ? " perspective" : " ortho"));
            test::expectNearCpuReference(gpu, cpu);
        }
    }
}

// A tile is a positive number of pixels a side, or 0 for the device's choice; a negative one is refused.
TEST(VulkanCasters, NegativeTileSizesAreRefused) {
    EXPECT_THROW(VulkanRenderer(test::vulkanContext(), -5), std::invalid_argument);
    EXPECT_EQ(VulkanRenderer(test::vulkanContext(), 16).tileSize(), 16);
    EXPECT_GT(VulkanRenderer(test::vulkanContext(), VulkanRenderer::kAutoTile).tileSize(), 0);
}

TEST(VulkanCasters, MatchCpuReferenceOnPhantoms) {
    for (const Dataset& d : phantoms()) expectMatchesCpu(d.name, prepare(d.volume, d.tf, 0.02, 10), false);
    expectNoValidationErrors();
}

TEST(VulkanCasters, MatchCpuReferenceOnRealDatasets) {
    for (const char* prefix : {"vtk_headsq_ct", "cranium_ct", "neghip", "boston_teapot"}) {
        const Dataset d = loadDataset(prefix, 48);
        expectMatchesCpu(d.name, prepare(d.volume, d.tf, 0.02, 10), false);
    }
    expectNoValidationErrors();
}

TEST(VulkanCasters, MatchCpuReferenceWithTrilinearSampling) {
    const Dataset d = loadDataset("vtk_headsq_ct", 40);
    expectMatchesCpu(d.name, prepare(d.volume, d.tf, 0.02, 10, true), true);
    const Volume shells = shellsPhantom({28, 28, 24});
    expectMatchesCpu("shells", prepare(shells, phantomTf(), 0.02, 10, true), true);
    expectNoValidationErrors();
}

TEST(VulkanCasters, MatchCpuReferenceWithDirectionalLightBackgroundAndOtherSteps) {
    const Dataset d = loadDataset("vtk_headsq_ct", 40);
    const PreparedVolume p = prepare(d.volume, d.tf, 0.02, 10);
    for (const ViewParams& vp : {view(20, 30), view(-60, 10, Projection::Perspective)}) {
        const Camera cam = Camera::fit(p.grid(), vp);
        for (Caster c : kCasters) {
            for (double step : {0.25, 1.7}) {  // 1.7: dt larger than a voxel
                RenderSettings s = renderSettings(c);
                s.lightDirection = Vec3d{1, -2, 0.5};
                s.background = {0.1, 0.2, 0.3};
                s.stepVoxels = step;
                s.ert = step > 1 ? 1.0 : 0.95;  // 1: no early termination
                const RenderResult gpu = renderer().render(p, cam, s);
                const RenderResult cpu = renderCpu(p, cam, s);
                SCOPED_TRACE(std::string(casterName(c)) + " step " + std::to_string(step));
                test::expectNearCpuReference(gpu, cpu);
            }
        }
    }
    expectNoValidationErrors();
}

// Tiny steps in a huge region: one leap stands for thousands of samples (docs/ALGORITHMS.md section 6).
TEST(VulkanCasters, LeapsOfThousandsOfSamplesMatchCpuReference) {
    const Volume v = constantPhantom({48, 48, 48}, 20);
    const PreparedVolume p = prepare(v, phantomTf(), 0, 0);
    ViewParams vp = view(33, 21);
    vp.width = vp.height = 16;
    const Camera cam = Camera::fit(v.grid, vp);
    for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD}) {
        RenderSettings s = renderSettings(c, false);
        s.stepVoxels = 0.002;
        const RenderResult gpu = renderer().render(p, cam, s);
        const RenderResult cpu = renderCpu(p, cam, s);
        EXPECT_LT(maxAbsDifference(gpu.image, cpu.image), 1e-3) << casterName(c);
        EXPECT_EQ(gpu.samples, cpu.samples) << casterName(c);
        EXPECT_GT(*std::max_element(gpu.samples.begin(), gpu.samples.end()), 10000u);
    }
    expectNoValidationErrors();
}

TEST(VulkanCasters, MissingFieldsAndIterationCapAreReported) {
    const Volume v = shellsPhantom({12, 12, 12});
    PreparedVolume p = prepare(v, phantomTf(), 0, 0);
    const Camera cam = Camera::fit(v.grid, view(0, 0));
    RenderSettings capped = renderSettings(Caster::Primitive);
    capped.maxIterationsPerRay = 2;
    EXPECT_THROW(renderer().render(p, cam, capped), std::runtime_error);
    p.fields = {};
    EXPECT_THROW(renderer().render(p, cam, renderSettings(Caster::EACD)), InputError);
    // Scalars that do not fill the grid, and a table without entries, are refused before anything is uploaded.
    PreparedVolume shortScalars = p;
    shortScalars.scalars.values.pop_back();
    EXPECT_THROW(renderer().render(shortScalars, cam, renderSettings(Caster::Primitive, false)), InputError);
    PreparedVolume noTable = p;
    noTable.classification.table = {};
    EXPECT_THROW(renderer().render(noTable, cam, renderSettings(Caster::Primitive, false)), InputError);
    // Shading needs nothing beyond the scalars.
    EXPECT_NO_THROW(renderer().render(p, cam, renderSettings(Caster::Primitive)));
    EXPECT_NO_THROW(renderer().render(p, cam, renderSettings(Caster::Primitive, false)));
    expectNoValidationErrors();
}

// The casters count a ray's samples in 32 bits: a longer lattice is refused before casting, naming --step and the
// device.
TEST(VulkanCasters, LatticeBeyondTheDeviceCountIsRefused) {
    const Volume v = constantPhantom({8, 8, 8}, 20);
    const PreparedVolume p = prepare(v, phantomTf(), 0, 0);
    RenderSettings s = renderSettings(Caster::EACD, false);
    s.stepVoxels = 1e-9;                // 1.4e10 samples across the volume
    s.maxIterationsPerRay = 1LL << 40;  // a cap that allows them
    try {
        renderer().render(p, Camera::fit(v.grid, view(0, 0)), s);
        ADD_FAILURE() << "rendered a lattice of more than 2^31 samples";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("too small for this volume on a Vulkan device"), std::string::npos) << what;
    }
}

// docs/ALGORITHMS.md section 5: with T_o = T_a = 0, nearest sampling and an orthographic view, every caster's image
// equals the primitive one (up to float rounding), on every dataset and phantom.
void expectCastersEqualPrimitive(const std::string& name, const PreparedVolume& p) {
    const std::vector<ViewParams> views{view(0, 0), view(90, 0), view(0, 90), view(180, 0),
                                        view(45, 35.264389682754654), view(-30, 20)};
    for (const ViewParams& vp : views) {
        const Camera cam = Camera::fit(p.grid(), vp);
        const RenderResult primitive = renderer().render(p, cam, renderSettings(Caster::Primitive));
        for (Caster c : {Caster::PC, Caster::ACD, Caster::EACD, Caster::Hier}) {
            SCOPED_TRACE(name + " " + std::string(casterName(c)) + " az " + std::to_string(vp.azimuthDeg) +
                         " el " + std::to_string(vp.elevationDeg));
            const RenderResult r = renderer().render(p, cam, renderSettings(c));
            EXPECT_LT(maxAbsDifference(r.image, primitive.image), 1e-4);
            EXPECT_LE(meanIterations(r), meanIterations(primitive));
        }
    }
}

TEST(VulkanCasters, EqualPrimitiveAtZeroThresholdsOnPhantoms) {
    for (const Dataset& d : phantoms()) expectCastersEqualPrimitive(d.name, prepare(d.volume, d.tf, 0, 0));
    expectNoValidationErrors();
}

TEST(VulkanCasters, EqualPrimitiveAtZeroThresholdsOnEveryDataset) {
    const auto entries = test::rawManifest();
    ASSERT_FALSE(entries.empty());
    for (const auto& e : entries) {
        const Dataset d = loadDataset(e, 40);
        expectCastersEqualPrimitive(d.name, prepare(d.volume, d.tf, 0, 0));
    }
    expectNoValidationErrors();
}

TEST(VulkanCasters, LeapingCutsIterationsOnCtDatasets) {
    for (const char* prefix : {"cranium_ct", "vtk_headsq_ct"}) {
        const Dataset d = loadDataset(prefix, 96);
        const PreparedVolume p = prepare(d.volume, d.tf, 0.05, 20);
        const Camera cam = Camera::fit(p.grid(), view(30, 20));
        double it[int(Caster::Hier) + 1] = {};
        for (Caster c : kCasters) it[int(c)] = meanIterations(renderer().render(p, cam, renderSettings(c)));
        SCOPED_TRACE(d.name);
        EXPECT_GT(it[0], it[1]);
        EXPECT_GT(it[1], it[2]);
        EXPECT_LE(it[3], it[2]);
        EXPECT_LT(it[int(Caster::Hier)], it[0]);
    }
    expectNoValidationErrors();
}

// 64^3 voxels of opacity 1e-9 each (per voxel step), seen along an axis: alpha = 1 - (1 - 1e-9)^64 at the
// centre, which float arithmetic of 1 - (1 - alpha)^n would lose entirely.
TEST(VulkanCasters, TinyOpacityAccumulatesOverConstantVolume) {
    const GridGeometry grid{{64, 64, 64}, {1, 1, 1}, {0, 0, 0}};
    const PreparedVolume p = test::syntheticPrepared(grid, 1.0, [](const Vec3i&) {
        return test::VoxelClass{1e-9, {1, 1, 1}};
    });
    const double expected = 1 - std::pow(1 - 1e-9, 64);
    ViewParams vp = view(0, 0);
    vp.width = vp.height = 33;  // an odd size: the centre pixel's ray is the volume's axis
    const Camera cam = Camera::fit(grid, vp);
    for (Caster c : kCasters) {
        const RenderResult r = renderer().render(p, cam, renderSettings(c, false));
        EXPECT_NEAR(r.image.pixel(16, 16)[3], expected, 0.01 * expected) << casterName(c);
    }
    expectNoValidationErrors();
}

std::set<std::string> uploadedNames() {
    std::set<std::string> names;
    for (const auto& [name, bytes] : test::bytesByName(renderer().lastUploads())) names.insert(name);
    return names;
}

std::size_t uploadedBytes(const std::string& name) {
    const auto bytes = test::bytesByName(renderer().lastUploads());
    return bytes.contains(name) ? bytes.at(name) : 0;
}

TEST(VulkanCasters, UploadOnlyWhatTheCasterAndViewUse) {
    const Volume v = shellsPhantom({20, 18, 16});
    const PreparedVolume p = prepare(v, phantomTf(), 0.02, 10);
    const std::size_t voxels = v.grid.voxels();
    const Camera ortho = Camera::fit(v.grid, view(30, 20));
    const Camera persp = Camera::fit(v.grid, view(0, 0, Projection::Perspective));

    renderer().render(p, ortho, renderSettings(Caster::Primitive));
    EXPECT_EQ(uploadedNames(), (std::set<std::string>{"scalars", "table"}));  // shaded: nothing more
    renderer().render(p, ortho, renderSettings(Caster::Primitive, false));
    EXPECT_EQ(uploadedNames(), (std::set<std::string>{"scalars", "table"}));
    EXPECT_EQ(uploadedBytes("scalars"), voxels * scalarBytes(v.sourceType));
    EXPECT_EQ(uploadedBytes("table"), p.classification.table.size() * 16);
    renderer().render(p, ortho, renderSettings(Caster::PC, false));
    EXPECT_EQ(uploadedBytes("pc"), voxels);
    renderer().render(p, ortho, renderSettings(Caster::ACD, false));
    EXPECT_EQ(uploadedBytes("acd"), voxels);  // one octant
    renderer().render(p, ortho, renderSettings(Caster::EACD));
    EXPECT_EQ(uploadedBytes("eacd"), voxels * 4);
    // Looking down -z from the centre line: the rays spread over x and y, never toward +z.
    EXPECT_EQ(viewOctants(persp), 0b11110000u);
    renderer().render(p, persp, renderSettings(Caster::ACD));
    EXPECT_EQ(uploadedBytes("acd"), voxels * 4);
    expectNoValidationErrors();
}

// volrender makes the pipeline of the caster asked while the volume is being prepared (preparePipeline): the one
// the render then takes, no other. (Not EACD: these volumes' EACD is in the exact code, not the default one that
// volrender prepares for.)
TEST(VulkanCasters, PreparedPipelineIsTheRendersOne) {
    const Volume v = shellsPhantom({20, 18, 16});
    const PreparedVolume p = prepare(v, phantomTf(), 0.02, 10);
    VulkanRenderer fresh(test::vulkanContext(), 40);
    std::size_t made = 0;
    for (Projection projection : {Projection::Orthographic, Projection::Perspective})
        for (Caster caster : {Caster::Primitive, Caster::PC, Caster::Hier}) {
            const RenderSettings s = renderSettings(caster);
            fresh.preparePipeline(s, projection, v.sourceType);
            EXPECT_EQ(fresh.pipelineCount(), ++made) << casterName(caster);
            fresh.render(p, Camera::fit(v.grid, view(30, 20, projection)), s);
            EXPECT_EQ(fresh.pipelineCount(), made) << casterName(caster);
        }
    expectNoValidationErrors();
}

TEST(VulkanCasters, PerspectiveOctantsCoverEveryPixelsRay) {
    const GridGeometry grid{{30, 20, 10}, {1, 1, 2}, {0, 0, 0}};
    for (double az : {0.0, 10.0, 45.0, 90.0, 133.0})
        for (double el : {0.0, 12.0, 60.0, -89.0}) {
            ViewParams vp = view(az, el, Projection::Perspective);
            vp.fovDeg = 100;
            const Camera cam = Camera::fit(grid, vp);
            unsigned seen = 0;
            for (int y = 0; y < vp.height; ++y)
                for (int x = 0; x < vp.width; ++x) {
                    const Vec3d d = cam.ray(x + 0.5, y + 0.5).direction;
                    seen |= 1u << octantOf(d.x, d.y, d.z);
                }
            const unsigned mask = viewOctants(cam);
            EXPECT_EQ(seen & ~mask, 0u) << "az " << az << " el " << el;
        }
}

}  // namespace
}  // namespace vr
