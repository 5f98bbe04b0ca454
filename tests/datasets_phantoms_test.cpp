// The synthetic phantoms the prepared-file, volprep and benchmark tests are built on.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/errors.h"
#include "datasets/phantoms.h"

namespace vr {
namespace {

void expectGrid(const Volume& v, Vec3i dims, Vec3d spacing) {
    EXPECT_EQ(v.grid.dims, dims);
    EXPECT_EQ(v.grid.spacing, spacing);
    EXPECT_EQ(v.values.size(), voxelCount(dims));
    EXPECT_EQ(v.source.rfind("phantom:", 0), 0u) << v.source;
}

TEST(DatasetsPhantoms, ConstantIsOneValue) {
    Volume v = constantPhantom({5, 6, 7}, 42, {1, 2, 3});
    expectGrid(v, {5, 6, 7}, {1, 2, 3});
    EXPECT_TRUE(std::all_of(v.values.begin(), v.values.end(), [](float f) { return f == 42; }));
}

TEST(DatasetsPhantoms, RampRisesAlongItsAxisOnly) {
    for (int axis = 0; axis < 3; ++axis) {
        Volume v = rampPhantom({4, 5, 6}, axis, 10, 20);
        Vec3i n = v.grid.dims;
        for (int z = 0; z < n.z; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x) {
                    Vec3i p(x, y, z);
                    EXPECT_FLOAT_EQ(v.at(x, y, z), 10 + 10.0f * float(p[axis]) / float(n[axis] - 1));
                }
    }
    EXPECT_EQ(rampPhantom({1, 1, 1}, 2, 3, 9).values[0], 3);  // a single slice takes the start value
    EXPECT_THROW(rampPhantom({2, 2, 2}, 3), InputError);
}

TEST(DatasetsPhantoms, ShellsHoldAirSoftTissueAndBoneInOrder) {
    Volume v = shellsPhantom({40, 40, 20}, {0.5, 0.5, 1.0});  // isotropic in world space
    expectGrid(v, {40, 40, 20}, {0.5, 0.5, 1.0});
    EXPECT_EQ(v.sourceType, ScalarType::Int16);
    std::set<float> values(v.values.begin(), v.values.end());
    EXPECT_EQ(values, (std::set<float>{-1000, 30, 40, 1000}));
    EXPECT_EQ(v.at(0, 0, 0), -1000);    // corner: air
    EXPECT_EQ(v.at(20, 20, 10), 30);    // centre: brain-like tissue
    EXPECT_EQ(v.at(20, 4, 10), 1000);   // r = 0.78 (in y, 0.5 mm voxels): bone
    EXPECT_EQ(v.at(20, 20, 19), -1000); // r = 0.95 along z (1 mm voxels): air, so the shells are round in mm
    EXPECT_EQ(v.at(1, 20, 10), -1000);
    EXPECT_EQ(v.at(2, 20, 10), 40);     // r = 0.875: the soft-tissue skin
}

TEST(DatasetsPhantoms, CheckerboardHasNoEqualFaceNeighbours) {
    Volume v = checkerboardPhantom({5, 4, 3}, 1, 2);
    Vec3i n = v.grid.dims;
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x) {
                EXPECT_TRUE(v.at(x, y, z) == 1 || v.at(x, y, z) == 2);
                if (x + 1 < n.x) {
                    EXPECT_NE(v.at(x, y, z), v.at(x + 1, y, z));
                }
                if (y + 1 < n.y) {
                    EXPECT_NE(v.at(x, y, z), v.at(x, y + 1, z));
                }
                if (z + 1 < n.z) {
                    EXPECT_NE(v.at(x, y, z), v.at(x, y, z + 1));
                }
            }
}

TEST(DatasetsPhantoms, NoiseIsReproducibleFromItsSeedAndInRange) {
    Volume a = noisePhantom({16, 16, 16}, 5, 10, 20), b = noisePhantom({16, 16, 16}, 5, 10, 20);
    Volume c = noisePhantom({16, 16, 16}, 6, 10, 20);
    EXPECT_EQ(a.values, b.values);
    EXPECT_NE(a.values, c.values);
    auto [lo, hi] = std::minmax_element(a.values.begin(), a.values.end());
    EXPECT_EQ(*lo, 10);
    EXPECT_EQ(*hi, 20);
    for (float f : a.values) EXPECT_EQ(f, std::round(f));
    EXPECT_THROW(noisePhantom({2, 2, 2}, 1, 5, 4), InputError);
}

TEST(DatasetsPhantoms, EngineIsBlockyWithABoreAndRibs) {
    Volume v = enginePhantom({64, 64, 64});
    std::set<float> values(v.values.begin(), v.values.end());
    EXPECT_EQ(values, (std::set<float>{0, 200, 255}));
    EXPECT_EQ(v.at(0, 0, 0), 0);      // air around the part
    EXPECT_EQ(v.at(32, 32, 32), 0);   // the bore through the middle
    EXPECT_EQ(v.at(15, 20, 40), 200); // the casting beside it, between ribs
    EXPECT_EQ(v.at(15, 20, 32), 255); // a rib
    // Blocky: most voxels equal their +x neighbour.
    std::size_t same = 0;
    for (int z = 0; z < 64; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x + 1 < 64; ++x) same += v.at(x, y, z) == v.at(x + 1, y, z);
    EXPECT_GT(double(same) / (63.0 * 64 * 64), 0.9);
}

TEST(DatasetsPhantoms, RejectEmptyGridsAndBadSpacing) {
    EXPECT_THROW(constantPhantom({0, 4, 4}), InputError);
    EXPECT_THROW(shellsPhantom({4, 4, 4}, {1, 0, 1}), InputError);
    EXPECT_THROW(enginePhantom({4, 4, -1}), InputError);
}

}  // namespace
}  // namespace vr
