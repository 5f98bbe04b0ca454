// A ray's pieces composited into its pixel (volrender/vulkan/ray_pieces.h), and how many pieces a device takes.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <vector>

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

// A CPU device casts whole rays; a GPU about a frame's worth of invocations, at most kMostPieces a ray.
TEST(VulkanRayPieces, PiecesFillTheDeviceAsAFrameDoes) {
    EXPECT_EQ(raysPieces(true, 1000, 262144), 1);
    EXPECT_EQ(raysPieces(false, 1000, 262144), kMostPieces);
    EXPECT_EQ(raysPieces(false, 100000, 262144), 2);
    EXPECT_EQ(raysPieces(false, 262144, 262144), 1);
    EXPECT_EQ(raysPieces(false, 0, 262144), 1);
}

// A renderer takes whole rays (1), up to kMostPieces, or the device's choice (0), and refuses the rest.
TEST(VulkanRayPieces, PieceCountsOutsideTheRangeAreRefused) {
    VulkanRenderer renderer(test::vulkanContext(), 16);
    for (int pieces : {0, 1, kMostPieces}) EXPECT_NO_THROW(renderer.setRecastPieces(pieces)) << pieces;
    for (int pieces : {-1, kMostPieces + 1}) EXPECT_THROW(renderer.setRecastPieces(pieces), std::invalid_argument);
}

}  // namespace
}  // namespace vr
