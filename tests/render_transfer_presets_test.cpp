// A built-in preset rendered: the shared head CT (Hounsfield units) with CT-Bone shows its skull and nothing of the
// air and soft tissue around it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "preprocess/classify/transfer_presets.h"
#include "render/cpu_renderer.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/views.h"
#include "support/volumes.h"

namespace vr {
namespace {

// The voxel columns along z whose values trilinear samples on a ray along z at world (x, y) blend: the two
// nearest voxel centres on each of x and y (clamped at the border).
std::array<Vec3i, 4> cornerColumns(const GridGeometry& grid, double x, double y) {
    const auto nearest = [](double world, double origin, double spacing, int dims) {
        const int i = int(std::floor((world - origin) / spacing - 0.5));
        return std::pair{std::clamp(i, 0, dims - 1), std::clamp(i + 1, 0, dims - 1)};
    };
    const auto [x0, x1] = nearest(x, grid.origin.x, grid.spacing.x, grid.dims.x);
    const auto [y0, y1] = nearest(y, grid.origin.y, grid.spacing.y, grid.dims.y);
    return {Vec3i{x0, y0, 0}, Vec3i{x1, y0, 0}, Vec3i{x0, y1, 0}, Vec3i{x1, y1, 0}};
}

float columnMax(const Volume& v, const Vec3i& column) {
    float m = -INFINITY;
    for (int z = 0; z < v.grid.dims.z; ++z) m = std::max(m, v.at(column.x, column.y, z));
    return m;
}

// Looking down z at the head, unshaded, with the primitive caster: a pixel whose ray meets only values at or
// below 150 HU (air, fat, water, brain, skin) is the background, exactly; one whose ray crosses bone (700 HU
// and above in each column its samples blend) is mostly opaque.
TEST(RenderTransferPresets, CtBoneShowsTheCraniumsSkullAndNothingElse) {
    const Volume ct = test::everyOtherVoxel(test::loadDataset("cranium_ct"));
    const PreparedVolume prepared =
        test::prepareVolume(ct, *findTransferPreset("CT-Bone"), {0, 0, false, true}, 0);
    const Camera camera = Camera::fit(ct.grid, test::orbitView(0, 0, 96, 96));
    ASSERT_NEAR(camera.forward.z, -1.0, 1e-12);
    RenderSettings settings = test::renderSettings(Caster::Primitive, false, true);
    const Image image = renderCpu(prepared, camera, settings).image;

    int clear = 0, bone = 0, opaqueBone = 0;
    for (int py = 0; py < image.height; ++py)
        for (int px = 0; px < image.width; ++px) {
            const Ray ray = camera.ray(px + 0.5, py + 0.5);
            float highest = -INFINITY, lowestColumnMax = INFINITY;
            for (const Vec3i& column : cornerColumns(ct.grid, ray.origin.x, ray.origin.y)) {
                const float m = columnMax(ct, column);
                highest = std::max(highest, m);
                lowestColumnMax = std::min(lowestColumnMax, m);
            }
            const float* rgba = image.pixel(px, py);
            if (highest <= 150) {
                ++clear;
                for (int c = 0; c < 4; ++c) ASSERT_EQ(rgba[c], 0.f) << px << "," << py << " max " << highest;
            } else if (lowestColumnMax >= 700) {
                ++bone;
                opaqueBone += rgba[3] > 0.5f;
            }
        }
    // Both kinds cover much of the image (the fitted view leaves the head a third of it), and the skull is opaque.
    EXPECT_GT(clear, 96 * 96 / 3);
    EXPECT_GT(bone, 96 * 96 / 10);
    EXPECT_GT(opaqueBone, bone * 95 / 100);
}

}  // namespace
}  // namespace vr
