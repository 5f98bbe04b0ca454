// Composite rays cast in pieces (volrender/vulkan/ray_pieces.h): how many pieces a device takes, frames cast in pieces
// against whole rays, and a failed piece failing its ray.
#include <gtest/gtest.h>

#include <string>

#include "support/render_cases.h"
#include "support/vulkan.h"
#include "volrender/vulkan/ray_pieces.h"

namespace vr {
namespace {

// A discrete GPU casts about a frame's worth of invocations, at most device::kMostPieces a ray; other devices whole
// rays.
TEST(VulkanRayPieces, PiecesFillTheDeviceAsAFrameDoes) {
    EXPECT_EQ(raysPieces(false, 1000, 262144), 1);
    EXPECT_EQ(raysPieces(true, 1000, 262144), device::kMostPieces);
    EXPECT_EQ(raysPieces(true, 100000, 262144), 2);
    EXPECT_EQ(raysPieces(true, 262144, 262144), 1);
    EXPECT_EQ(raysPieces(true, 0, 262144), 1);
}

// Translucent shells over an opaque core, at thresholds 0: long rays whose colour every stretch adds to.
const PreparedVolume& shells() {
    const GridGeometry grid{{24, 20, 28}, {1, 1, 1}, {0, 0, 0}};
    static const PreparedVolume p = test::syntheticPrepared(grid, 1.0, [](const Vec3i& v) {
        const double r = length(Vec3d(v) - Vec3d{11.5, 9.5, 13.5});
        if (r < 3) return test::VoxelClass{0.9, {1, 1, 1}};
        if (r < 8) return test::VoxelClass{0.03 * (1 + int(r) % 3), {0.3 * (int(r) % 2), 0.5, 0.2 + 0.1 * int(r)}};
        return test::VoxelClass{0.0, {0, 0, 0}};
    });
    return p;
}

// A whole frame's rays in pieces give the whole rays' image, stepped and leapt (shaded where the regions allow), in
// orthographic and perspective views, with fewer rows a tile: to float rounding without early ray termination, and
// within its tolerance (1 - ert of the colour, which the whole ray leaves out) with it. A volume of bricks casts whole
// rays whatever it is asked.
TEST(VulkanRayPieces, FramesInPiecesAreTheWholeRaysFrames) {
    VulkanRenderer whole(test::vulkanContext(), 16), pieced(test::vulkanContext(), 16);
    const GpuVolume a = whole.upload(shells(), {{Caster::Primitive, Caster::EACD}, kAllOctants});
    const GpuVolume b = pieced.upload(shells(), {{Caster::Primitive, Caster::EACD}, kAllOctants});
    for (Projection projection : {Projection::Orthographic, Projection::Perspective})
        for (Caster caster : {Caster::Primitive, Caster::EACD})
            for (double ert : {1.0, 0.99}) {
                const Camera camera = Camera::fit(shells().grid(), test::orbitView(30, 20, 40, 36, projection));
                RenderSettings s = test::renderSettings(caster, caster == Caster::Primitive);
                s.ert = ert;
                const RenderResult one = whole.render(a, camera, s);
                for (int pieces : {2, 3, device::kMostPieces}) {
                    const std::string what = std::string(casterName(caster)) + ", " + std::to_string(pieces) +
                                             " pieces, ert " + std::to_string(ert) +
                                             (projection == Projection::Perspective ? ", perspective" : "");
                    pieced.setRayPieces(pieces);
                    const RenderResult split = pieced.render(b, camera, s);
                    EXPECT_LE(maxAbsDifference(split.image, one.image), 1 - ert + 1e-5) << what;
                    std::uint64_t wholeIterations = 0, pieceIterations = 0;
                    for (std::size_t i = 0; i < one.iterations.size(); ++i) {
                        wholeIterations += one.iterations[i];
                        pieceIterations += split.iterations[i];
                    }
                    if (caster == Caster::EACD) {
                        EXPECT_GT(pieceIterations, wholeIterations) << what;
                    } else {
                        EXPECT_GE(pieceIterations, wholeIterations) << what;
                    }
                }
            }
    VulkanRenderer bricked(test::vulkanContext(), 16, ImageLimits{.maxDimension = 40, .minBricks = {2, 2, 2}});
    bricked.setRayPieces(4);
    const GpuVolume split = bricked.upload(shells(), {{Caster::EACD}, kAllOctants});
    ASSERT_GT(split.bricks().bricks().size(), 1u);
    const Camera camera = Camera::fit(shells().grid(), test::orbitView(30, 20, 40, 36));
    const RenderSettings s = test::renderSettings(Caster::EACD, false);
    EXPECT_LE(maxAbsDifference(bricked.render(split, camera, s).image, whole.render(a, camera, s).image), 1e-5);
    test::expectNoValidationErrors();
}

// A piece that hits the iteration cap fails its ray, and the render, as a whole ray would.
TEST(VulkanRayPieces, AFailedPieceFailsTheRender) {
    VulkanRenderer renderer(test::vulkanContext(), 16);
    renderer.setRayPieces(4);
    const GpuVolume volume = renderer.upload(shells(), {{Caster::Primitive}, kAllOctants});
    RenderSettings s = test::renderSettings(Caster::Primitive, false);
    s.maxIterationsPerRay = 2;
    const Camera camera = Camera::fit(shells().grid(), test::orbitView(30, 20, 24, 20));
    EXPECT_THROW(renderer.render(volume, camera, s), std::runtime_error);
    s.rayCounts = false;
    EXPECT_THROW(renderer.render(volume, camera, s), std::runtime_error);
    test::expectNoValidationErrors();
}

// A renderer takes whole rays (1) or up to device::kMostPieces, for re-casts also the device's choice (0), and
// refuses the rest.
TEST(VulkanRayPieces, PieceCountsOutsideTheRangeAreRefused) {
    VulkanRenderer renderer(test::vulkanContext(), 16);
    for (int pieces : {0, 1, device::kMostPieces}) EXPECT_NO_THROW(renderer.setRecastPieces(pieces)) << pieces;
    for (int pieces : {-1, device::kMostPieces + 1})
        EXPECT_THROW(renderer.setRecastPieces(pieces), std::invalid_argument) << pieces;
    for (int pieces : {1, device::kMostPieces}) EXPECT_NO_THROW(renderer.setRayPieces(pieces)) << pieces;
    for (int pieces : {0, device::kMostPieces + 1}) EXPECT_THROW(renderer.setRayPieces(pieces), std::invalid_argument);
}

}  // namespace
}  // namespace vr
