// A ray's pieces composited into its pixel (volrender/vulkan/ray_pieces.h), how many pieces a device takes, and frames
// cast in pieces.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <vector>

#include "support/render_cases.h"
#include "support/vulkan.h"
#include "volrender/vulkan/ray_pieces.h"

namespace vr {
namespace {

device::uvec4 piece(float r, float g, float b, float depth) {
    return {std::bit_cast<uint32_t>(r), std::bit_cast<uint32_t>(g), std::bit_cast<uint32_t>(b),
            std::bit_cast<uint32_t>(depth)};
}

float channel(uint32_t bits) { return std::bit_cast<float>(bits); }

// Two pieces of a ray, interleaved with another ray's at a stride of 2: the second is seen through the first's
// transmittance e^-d1, and the background through both.
TEST(VulkanRayPieces, PiecesCompositeFrontToBackOverTheBackground) {
    const std::vector<device::uvec4> colours{piece(0.2f, 0.1f, 0.0f, 0.5f), piece(9, 9, 9, 9),
                                             piece(0.4f, 0.0f, 0.3f, 1.0f), piece(9, 9, 9, 9)};
    const std::vector<device::uvec4> counts{{10, 3, 0, 0}, {0, 0, 0, 0}, {12, 4, 0, 0}, {0, 0, 0, 0}};
    const Vec3d background{0.1, 0.2, 0.3};
    const RayFromPieces ray = compositePieces(colours.data(), counts.data(), 0, 2, 2, background);
    const double t1 = std::exp(-0.5), alpha = 1 - std::exp(-1.5);
    EXPECT_NEAR(channel(ray.colour.x), 0.2 + t1 * 0.4 + 0.1 * (1 - alpha), 1e-6);
    EXPECT_NEAR(channel(ray.colour.y), 0.1 + 0.2 * (1 - alpha), 1e-6);
    EXPECT_NEAR(channel(ray.colour.z), t1 * 0.3 + 0.3 * (1 - alpha), 1e-6);
    EXPECT_NEAR(channel(ray.colour.w), alpha, 1e-6);
    EXPECT_EQ(ray.samples, 22u);
    EXPECT_EQ(ray.iterations, 7u);
}

// One piece is the whole ray: its pixel is the caster's own (colour over the background, alpha from the depth).
TEST(VulkanRayPieces, OnePieceIsTheWholeRaysPixel) {
    const std::vector<device::uvec4> colours{piece(0.25f, 0.5f, 0.125f, 2.0f)};
    const RayFromPieces ray = compositePieces(colours.data(), nullptr, 0, 1, 1, {0, 0, 0});
    EXPECT_EQ(channel(ray.colour.x), 0.25f);
    EXPECT_EQ(channel(ray.colour.y), 0.5f);
    EXPECT_EQ(channel(ray.colour.z), 0.125f);
    EXPECT_NEAR(channel(ray.colour.w), 1 - std::exp(-2.0), 1e-7);
    EXPECT_EQ(ray.samples, 0u);
}

// A piece that failed (its alpha a failure NaN, its counts flagged) fails the ray, in its colour and its counts.
TEST(VulkanRayPieces, AFailedPieceFailsTheRay) {
    std::vector<device::uvec4> colours{piece(0.1f, 0.1f, 0.1f, 0.1f), piece(0.1f, 0.1f, 0.1f, 0.1f)};
    colours[1].w = device::failureAlphaBits(device::kFailed);
    const std::vector<device::uvec4> counts{{5, 2, 0, 0}, {5, 2 | device::kFailed, 0, 0}};
    const RayFromPieces ray = compositePieces(colours.data(), counts.data(), 0, 1, 2, {0, 0, 0});
    EXPECT_EQ(device::failureFlagsOf(ray.colour.w), device::kFailed);
    EXPECT_EQ(ray.iterations, 4u | device::kFailed);
    colours[1].w = std::bit_cast<uint32_t>(0.1f);
    colours[0].w = device::failureAlphaBits(device::kCutShort);
    EXPECT_EQ(device::failureFlagsOf(compositePieces(colours.data(), nullptr, 0, 1, 2, {0, 0, 0}).colour.w),
              device::kCutShort);
}

// A discrete GPU casts about a frame's worth of invocations, at most kMostPieces a ray; other devices whole rays.
TEST(VulkanRayPieces, PiecesFillTheDeviceAsAFrameDoes) {
    EXPECT_EQ(raysPieces(false, 1000, 262144), 1);
    EXPECT_EQ(raysPieces(true, 1000, 262144), kMostPieces);
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
                for (int pieces : {2, 3, kMostPieces}) {
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

// A renderer takes whole rays (1) or up to kMostPieces, for re-casts also the device's choice (0), and refuses the
// rest.
TEST(VulkanRayPieces, PieceCountsOutsideTheRangeAreRefused) {
    VulkanRenderer renderer(test::vulkanContext(), 16);
    for (int pieces : {0, 1, kMostPieces}) EXPECT_NO_THROW(renderer.setRecastPieces(pieces)) << pieces;
    for (int pieces : {-1, kMostPieces + 1}) EXPECT_THROW(renderer.setRecastPieces(pieces), std::invalid_argument);
    for (int pieces : {1, kMostPieces}) EXPECT_NO_THROW(renderer.setRayPieces(pieces)) << pieces;
    for (int pieces : {0, kMostPieces + 1}) EXPECT_THROW(renderer.setRayPieces(pieces), std::invalid_argument);
}

}  // namespace
}  // namespace vr
