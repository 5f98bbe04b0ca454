// --caster auto's choice (volrender/caster_choice.h) on hand-made statistics of the form preparedStatistics writes.
#include <gtest/gtest.h>

#include "core/distance_fields.h"
#include "volrender/caster_choice.h"

namespace vr {
namespace {
using json = nlohmann::json;

// Statistics of a 256^3 volume: PC radius, ACD edge and EACD extents alike in every octant; a field is absent
// (no bytes, no leaps) when its leap is 0.
json statistics(double pcRadius, double acdEdge, std::array<double, 3> eacdExtent, double voxels = 256.0 * 256 * 256) {
    json s{{"voxels", voxels}, {"regions", 1000}, {"meanRegionSize", voxels / 1000}};
    json leaps = json::object(), bytes{{"sigma", 4 * voxels}, {"colour", 12 * voxels}};
    if (pcRadius > 0) {
        leaps["pcMeanRadius"] = pcRadius;
        bytes["pc"] = voxels;
    }
    if (acdEdge > 0) {
        leaps["acdMeanEdge"] = json(std::vector<double>(kOctants, acdEdge));
        bytes["acd"] = 8 * voxels;
    }
    if (eacdExtent[0] > 0) {
        leaps["eacdMeanExtent"] = json(std::vector<std::array<double, 3>>(kOctants, eacdExtent));
        bytes["eacd"] = 24 * voxels;
    }
    s["leaps"] = leaps;
    s["bytes"] = bytes;
    return s;
}

CasterDemand ortho(Vec3d direction = {0, 0, -1}) {
    CasterDemand d;
    d.direction = direction;
    d.octants = 1u << octantOf(direction.x, direction.y, direction.z);
    return d;
}

TEST(CasterChoice, NoStatisticsOrNoFieldsGivesPrimitive) {
    EXPECT_EQ(chooseCaster(json::object(), ortho()).caster, Caster::Primitive);
    EXPECT_EQ(chooseCaster(json(nullptr), ortho()).caster, Caster::Primitive);
    EXPECT_EQ(chooseCaster(statistics(0, 0, {0, 0, 0}), ortho()).caster, Caster::Primitive);
}

TEST(CasterChoice, TakesTheLongestLeapAmongTheFieldsPresent) {
    EXPECT_EQ(chooseCaster(statistics(6, 0, {0, 0, 0}), ortho()).caster, Caster::PC);
    EXPECT_EQ(chooseCaster(statistics(6, 12, {0, 0, 0}), ortho()).caster, Caster::ACD);
    EXPECT_EQ(chooseCaster(statistics(6, 12, {30, 30, 30}), ortho()).caster, Caster::EACD);
    // A PC radius near 0 leaps no further than a step and pays for its fetches: primitive, not PC.
    EXPECT_EQ(chooseCaster(statistics(0.05, 0, {0, 0, 0}), ortho()).caster, Caster::Primitive);
}

TEST(CasterChoice, LeapsShorterThanTheStepCountAsOneStep) {
    // Every caster moves at least one step per iteration: a step longer than EACD's extents leaves it no longer
    // leaps than ACD's, at a dearer iteration.
    CasterDemand d = ortho();
    EXPECT_EQ(chooseCaster(statistics(2, 3, {6, 6, 6}), d).caster, Caster::EACD);
    d.stepVoxels = 8;
    EXPECT_EQ(chooseCaster(statistics(2, 3, {6, 6, 6}), d).caster, Caster::ACD);
}

TEST(CasterChoice, EacdNoLongerThanAcdGivesTheLeanerAcd) {
    // EACD's extents equal ACD's edge: the same iterations for three times the bytes.
    EXPECT_EQ(chooseCaster(statistics(4, 10, {10, 10, 10}), ortho()).caster, Caster::ACD);
    EXPECT_EQ(chooseCaster(statistics(4, 10, {10.2, 10.2, 10.2}), ortho()).caster, Caster::ACD);
}

TEST(CasterChoice, EacdLeapDependsOnTheViewDirection) {
    // Boxes long in x and y, thin in z: a view along z leaves them after 2 voxels, a view along x after 40.
    const json s = statistics(1.5, 2.5, {40, 40, 2.5});
    EXPECT_EQ(chooseCaster(s, ortho({0, 0, -1})).caster, Caster::ACD);
    EXPECT_EQ(chooseCaster(s, ortho({1, 0, 0})).caster, Caster::EACD);
}

TEST(CasterChoice, OnlyTheViewsOctantsCount) {
    json s = statistics(0.5, 1, {1, 1, 1});                // every voxel a region of its own, but long ACD
    s["leaps"]["acdMeanEdge"][0] = 40;                       // leaps in octant 0 (+x +y +z) and long EACD
    s["leaps"]["eacdMeanExtent"][7] = json({40, 40, 40});    // leaps in octant 7 (-x -y -z)
    EXPECT_EQ(chooseCaster(s, ortho({1, 1, 1})).caster, Caster::ACD);
    EXPECT_EQ(chooseCaster(s, ortho({-1, -1, -1})).caster, Caster::EACD);
}

TEST(CasterChoice, ATinyImageDoesNotPayForAHugeUpload) {
    const json s = statistics(8, 20, {40, 40, 40}, 512.0 * 512 * 512);
    CasterDemand d = ortho();
    d.views = 100;  // an orbit sharing one upload
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::EACD);
    d.pixels = 16;  // 4x4 pixels: rendering costs less than uploading any field
    d.views = 1;
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::Primitive);
}

TEST(CasterChoice, PerspectiveUploadsEveryOctantItsRaysHave) {
    // A slightly longer EACD leap pays for one octant's bytes, not for all eight: then ACD (a third of the bytes).
    const json s = statistics(8, 20, {60, 60, 60}, 512.0 * 512 * 512);
    CasterDemand d = ortho();
    d.pixels = 1024 * 1024;
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::EACD);
    d.projection = Projection::Perspective;
    d.octants = 0xff;
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::ACD);
}

TEST(CasterChoice, SaysWhy) {
    // Every candidate with its estimated leap and relative cost.
    const CasterChoice c = chooseCaster(statistics(6, 12, {30, 30, 30}), ortho());
    for (const char* caster : {"primitive 0.50, 1.000", "pc 6.50,", "acd 11.50,", "eacd 29.50,"})
        EXPECT_NE(c.reason.find(caster), std::string::npos) << c.reason;
}

}  // namespace
}  // namespace vr
