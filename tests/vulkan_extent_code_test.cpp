// Coded EACD on the device: the EACD caster decodes log16 (R16_UINT) and joint8 (R8_UINT) texels through the table
// core/extent_code.cpp states, so it renders what the CPU reference renders from the same rounded-down boxes, ray
// by ray, and uploads 2 or 1 bytes per voxel and octant.
#include <gtest/gtest.h>

#include "datasets/phantoms.h"
#include "render/cpu_renderer.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/volumes.h"
#include "support/vulkan.h"

namespace vr {
namespace {

constexpr ExtentCode kCodes[] = {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8};

VulkanRenderer& renderer() { return test::vulkanRenderer(40); }

PreparedVolume prepare(const Volume& volume, const std::string& tf, double to, double ta, bool trilinear) {
    return test::prepareVolume(volume, test::datasetTransferFunction(tf), {to, ta, true, trilinear}, kFieldEACD);
}

ViewParams view(double az, double el, Projection projection = Projection::Orthographic) {
    return test::orbitView(az, el, 64, 48, projection);
}

// Every code on the device against the CPU reference on the same coded volume, in orthographic and perspective
// views (one and several octants uploaded).
void expectEveryCodeMatchesCpu(const PreparedVolume& exact, bool trilinear, const std::string& what) {
    RenderSettings s;
    s.caster = Caster::EACD;
    s.trilinear = trilinear;
    for (ExtentCode code : kCodes) {
        PreparedVolume p = exact;
        quantiseEACD(p.fields, code);
        for (const ViewParams& vp : {view(37, 23), view(-120, -35), view(30, -20, Projection::Perspective)}) {
            const Camera cam = Camera::fit(p.grid(), vp);
            const RenderResult gpu = renderer().render(p, cam, s);
            const RenderResult cpu = renderCpu(p, cam, s);
            SCOPED_TRACE(what + " " + std::string(extentCodeName(code)) + " az " + std::to_string(vp.azimuthDeg));
            test::expectNearCpuReference(gpu, cpu);
        }
    }
}

TEST(VulkanExtentCode, EveryCodeMatchesTheCpuReferenceOnPhantoms) {
    expectEveryCodeMatchesCpu(prepare(shellsPhantom({36, 36, 30}, {1, 1, 1.5}), "cranium_ct.tf.json", 0.02, 10, false),
                              false, "shells");
    expectEveryCodeMatchesCpu(prepare(enginePhantom({40, 32, 24}), "mri.tf.json", 0, 0, true), true,
                              "engine trilinear");
}

TEST(VulkanExtentCode, EveryCodeMatchesTheCpuReferenceOnTheTeapot) {
    // The long runs of air around the teapot give extents past 16 (log16's geometric part) and past 50 (joint8's
    // top level); a downsampled copy keeps the test quick.
    const test::DatasetEntry teapot = test::rawDataset("boston_teapot");
    const PreparedVolume p = prepare(test::everyOtherVoxel(test::loadDataset(teapot)), teapot.tf, 0.02, 10, false);
    int longest = 0;
    for (std::size_t v = 0; v < p.fields.eacd[0].size(); ++v) {
        const Extents e = p.fields.eacd[0][v];
        longest = std::max({longest, int(e[0]), int(e[1]), int(e[2])});
    }
    EXPECT_GT(longest, 50);
    expectEveryCodeMatchesCpu(p, false, teapot.file);
}

TEST(VulkanExtentCode, UploadsTheCodedBytes) {
    const Volume v = shellsPhantom({20, 18, 16});
    const std::size_t voxels = v.grid.voxels();
    const PreparedVolume exact = prepare(v, "cranium_ct.tf.json", 0.02, 10, false);
    RenderSettings s;
    s.caster = Caster::EACD;
    const Camera ortho = Camera::fit(v.grid, view(30, 20));  // one octant
    for (auto [code, bytes] : {std::pair{ExtentCode::Exact, 4u}, std::pair{ExtentCode::Log16, 2u},
                               std::pair{ExtentCode::Joint8, 1u}}) {
        PreparedVolume p = exact;
        quantiseEACD(p.fields, code);
        renderer().render(p, ortho, s);
        EXPECT_EQ(test::bytesByName(renderer().lastUploads())["eacd"], voxels * bytes) << extentCodeName(code);
    }
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
