// Classification of volumes: the transfer table, gradients and normals, extinction, TF lookups, bad parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/errors.h"
#include "preprocess/classify/classify.h"
#include "core/gradient.h"
#include "preprocess/load/load_volume.h"
#include "support/load_dataset.h"
#include "support/volumes.h"

namespace vr {
namespace {

TEST(ClassifyVolume, GradientOfALinearRampIsInPhysicalUnits) {
    const Vec3d spacing{0.5, 2.0, 4.0};
    const Volume v = test::volumeOf({7, 5, 4}, spacing, ScalarType::Float32,
                                [](int x, int y, int z) { return 2.0 * x + 3.0 * y + 5.0 * z; });
    const Vec3d expected{2 / 0.5, 3 / 2.0, 5 / 4.0};
    for (int z = 0; z < 4; ++z)  // borders included: one-sided differences are exact on a ramp
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 7; ++x) {
                const Vec3d g = centralGradient(v, x, y, z);
                EXPECT_NEAR(g.x, expected.x, 1e-12);
                EXPECT_NEAR(g.y, expected.y, 1e-12);
                EXPECT_NEAR(g.z, expected.z, 1e-12);
            }
    // Central, not one-sided, in the interior: f = x^2 gives 2x / h exactly.
    const Volume q =
        test::volumeOf({6, 1, 1}, {0.25, 1, 1}, ScalarType::Float32, [](int x, int, int) { return x * x; });
    EXPECT_DOUBLE_EQ(centralGradient(q, 2, 0, 0).x, (9.0 - 1.0) / 0.5);
    EXPECT_DOUBLE_EQ(centralGradient(q, 0, 0, 0).x, 1.0 / 0.25);
    EXPECT_DOUBLE_EQ(centralGradient(q, 5, 0, 0).x, (25.0 - 16.0) / 0.25);
    EXPECT_DOUBLE_EQ(centralGradient(q, 3, 0, 0).y, 0.0);  // a single-voxel axis has no derivative

    ClassifyParams params;
    params.transferFunction = test::linearTransferFunction(0, 100);
    const ClassifiedVolume c = classify(v, params);
    ASSERT_TRUE(c.hasNormals());
    const Vec3d n = normalize(expected);
    for (const auto& normal : c.normal) {
        EXPECT_NEAR(normal[0], n.x, 1e-6);
        EXPECT_NEAR(normal[1], n.y, 1e-6);
        EXPECT_NEAR(normal[2], n.z, 1e-6);
    }
}

TEST(ClassifyVolume, NormalsAreTheNormalisedCentralGradientBitForBit) {
    // Any shape (axes of 1 and 2 voxels included) and uneven spacing: classify's row-wise gradients are gradient.h's.
    std::mt19937 rng(9);
    std::uniform_int_distribution<int> values(0, 255);
    for (Vec3i dims : {Vec3i{7, 6, 5}, Vec3i{1, 4, 3}, Vec3i{2, 1, 6}, Vec3i{5, 2, 1}, Vec3i{1, 1, 4}}) {
        const Volume v =
            test::volumeOf(dims, {0.7, 1.3, 2.1}, ScalarType::UInt8, [&](int, int, int) { return values(rng); });
        ClassifyParams params;
        params.transferFunction = test::linearTransferFunction(0, 255);
        const ClassifiedVolume c = classify(v, params);
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const Vec3d g = centralGradient(v, x, y, z);
                    const double m = length(g);
                    // Integer values: a gradient is 0 or far above the flat floor.
                    const std::array<float, 3> n = m > 0 ? std::array<float, 3>{float(g.x / m), float(g.y / m),
                                                                                float(g.z / m)}
                                                         : std::array<float, 3>{0, 0, 0};
                    ASSERT_EQ(c.normal[linearIndex(dims, x, y, z)], n) << x << "," << y << "," << z;
                }
    }
}

TEST(ClassifyVolume, IntoAUsedVolumeEqualsAFreshOne) {
    std::mt19937 rng(4);
    std::uniform_int_distribution<int> values(0, 255);
    const Volume big =
        test::volumeOf({9, 8, 7}, {1, 1, 1}, ScalarType::UInt8, [&](int, int, int) { return values(rng); });
    const Volume small =
        test::volumeOf({4, 5, 3}, {0.5, 1, 2}, ScalarType::UInt8, [&](int, int, int) { return values(rng); });
    ClassifyParams params;
    params.transferFunction = test::linearTransferFunction(10, 200);
    ClassifiedVolume reused = classify(big, params);
    for (const Volume* v : {&small, &big, &big})
        for (bool normals : {false, true}) {
            params.normals = normals;
            classify(*v, scalarClassification(*v, params), normals, reused);
            const ClassifiedVolume fresh = classify(*v, params);
            EXPECT_EQ(reused.grid, fresh.grid);
            EXPECT_EQ(reused.referenceStep, fresh.referenceStep);
            EXPECT_EQ(reused.sigma, fresh.sigma);
            EXPECT_EQ(reused.colour, fresh.colour);
            EXPECT_EQ(reused.normal, fresh.normal);
        }
}

// The table the renderers look samples up in: an entry per integer from the smallest to the largest voxel of an
// integer volume, sigma converted from the TF's opacity per dt0, and the flat length from the value range.
TEST(ClassifyVolume, ScalarClassificationTabulatesTheTransferFunction) {
    const Volume v =
        test::volumeOf({5, 2, 2}, {2, 1, 0.5}, ScalarType::Int16, [](int x, int, int) { return 10 * x - 3; });
    ClassifyParams params;
    params.transferFunction = test::linearTransferFunction(0, 40);
    const ScalarClassification c = scalarClassification(v, params);
    EXPECT_DOUBLE_EQ(c.table.lo, -3);
    EXPECT_DOUBLE_EQ(c.table.step, 1);
    ASSERT_EQ(c.table.size(), 41u);  // -3 .. 37
    EXPECT_DOUBLE_EQ(c.referenceStep, 0.5);
    EXPECT_DOUBLE_EQ(c.flatGradient, 1e-6 * 40 / 0.5);
    for (std::size_t k = 0; k < c.table.size(); ++k) {
        const double f = -3.0 + double(k);
        EXPECT_EQ(c.table.sigma[k], float(extinctionFromOpacity(params.transferFunction->opacityAt(f), 0.5))) << f;
    }
    // The classified volume is the table at each voxel (every voxel of an integer volume lies on an entry).
    const ClassifiedVolume cv = classify(v, params);
    for (std::size_t i = 0; i < v.values.size(); ++i) {
        const std::size_t k = std::size_t(v.values[i] + 3);
        EXPECT_EQ(cv.sigma[i], c.table.sigma[k]);
        EXPECT_EQ(cv.colour[i], c.table.colour[k]);
    }
}

TEST(ClassifyVolume, FlatRegionsHaveZeroNormals) {
    // A plateau (x < 4) beside a ramp: zero gradient is flat, never normalize(0).
    const Volume v = test::volumeOf({10, 3, 3}, {1, 1, 1}, ScalarType::UInt8,
                                [](int x, int, int) { return x < 4 ? 7.0 : 7.0 + 10 * (x - 4); });
    ClassifyParams params;
    params.transferFunction = test::linearTransferFunction(0, 255);
    const ClassifiedVolume c = classify(v, params);
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 10; ++x) {
                const auto& n = c.normal[linearIndex(v.grid.dims, x, y, z)];
                for (float component : n) EXPECT_TRUE(std::isfinite(component));
                if (x < 4) {  // x = 3 sees 7 on both sides
                    EXPECT_EQ(n, (std::array<float, 3>{0, 0, 0})) << x;
                } else {
                    EXPECT_NEAR(n[0], 1.0f, 1e-6) << x;
                }
            }
    // A constant volume: every voxel flat; without normals none are stored.
    const Volume constant = test::volumeOf({4, 4, 4}, {1, 1, 1}, ScalarType::UInt8, [](int, int, int) { return 9; });
    for (const auto& n : classify(constant, params).normal) EXPECT_EQ(n, (std::array<float, 3>{0, 0, 0}));
    params.normals = false;
    EXPECT_FALSE(classify(constant, params).hasNormals());
}

TEST(ClassifyVolume, ExtinctionRoundTrip) {
    for (double dt0 : {1.0, 0.5, 3.0}) {
        EXPECT_EQ(extinctionFromOpacity(0.0, dt0), 0.0);
        EXPECT_EQ(opacityFromExtinction(0.0, dt0), 0.0);
        for (double alpha : {1e-9, 1e-4, 0.25, 0.5, 0.999}) {
            const double sigma = extinctionFromOpacity(alpha, dt0);
            EXPECT_NEAR(opacityFromExtinction(sigma, dt0) / alpha, 1.0, 1e-12) << alpha;
            // Stored as float: relative precision of a float.
            EXPECT_NEAR(opacityFromExtinction(float(sigma), dt0) / alpha, 1.0, 1e-6) << alpha;
            // Any span L: alpha_L = 1 - (1 - alpha)^(L / dt0).
            EXPECT_NEAR(opacityFromExtinction(sigma, 3 * dt0), 1 - std::pow(1 - alpha, 3), 1e-12);
        }
        const double opaque = extinctionFromOpacity(1.0, dt0);
        EXPECT_TRUE(std::isfinite(opaque));
        EXPECT_TRUE(std::isfinite(float(opaque)));
        EXPECT_GT(opacityFromExtinction(opaque, dt0), 1 - 1e-11);
    }
}

TEST(ClassifyVolume, OpacityAndColourFollowTheTransferFunctionPerReferenceStep) {
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> values(-1024, 2986);
    const Volume ct = test::volumeOf({11, 9, 7}, {0.7, 0.7, 1.5}, ScalarType::Int16,
                                 [&](int, int, int) { return values(rng); });
    ClassifyParams params;
    params.transferFunction = test::datasetTransferFunction("cranium_ct.tf.json");
    params.transferFunction->opacity.back().opacity = 1.0;  // include opaque voxels
    for (double referenceStep : {0.0, 2.5}) {
        params.referenceStep = referenceStep;
        const ClassifiedVolume c = classify(ct, params);
        EXPECT_DOUBLE_EQ(c.referenceStep, referenceStep == 0 ? 0.7 : 2.5);
        EXPECT_EQ(c.grid, ct.grid);
        for (std::size_t i = 0; i < ct.values.size(); ++i) {
            const double alpha = params.transferFunction->opacityAt(ct.values[i]);
            ASSERT_TRUE(std::isfinite(c.sigma[i]));
            EXPECT_NEAR(c.opacity(i), alpha, 1e-6 * std::max(alpha, 1e-3)) << ct.values[i];
            if (alpha == 0) {
                EXPECT_EQ(c.sigma[i], 0.0f);
            }
            const auto rgb = params.transferFunction->colourAt(ct.values[i]);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.colour[i][k], rgb[k], 1e-6);
        }
    }
    // Float volumes use an interpolated table over their range.
    std::uniform_real_distribution<double> real(0, 1000);
    const Volume f =
        test::volumeOf({8, 8, 8}, {1, 1, 1}, ScalarType::Float32, [&](int, int, int) { return real(rng); });
    TransferFunction tf;
    tf.opacity = {{0, 0}, {300, 0.2, 0.3, 0.4}, {800, 0.9}, {1000, 0.1}};
    params.transferFunction = tf;
    params.referenceStep = 0;
    const ClassifiedVolume c = classify(f, params);
    for (std::size_t i = 0; i < f.values.size(); ++i) EXPECT_NEAR(c.opacity(i), tf.opacityAt(f.values[i]), 1e-4);
}

TEST(ClassifyVolume, BadParametersAreInputErrors) {
    const Volume v = test::volumeOf({3, 3, 3}, {1, 1, 1}, ScalarType::UInt8, [](int x, int, int) { return x; });
    ClassifyParams none;
    EXPECT_THROW(classify(v, none), InputError);
    ClassifyParams negativeStep;
    negativeStep.transferFunction = test::linearTransferFunction(0, 1);
    negativeStep.referenceStep = -1;
    EXPECT_THROW(classify(v, negativeStep), InputError);
    ClassifyParams good;
    good.transferFunction = test::linearTransferFunction(0, 1);
    EXPECT_NO_THROW(classify(v, good));
    Volume nan = v;
    nan.values[13] = std::nanf("");
    EXPECT_THROW(classify(nan, good), InputError);
    ClassifyParams unsorted;
    unsorted.transferFunction = test::linearTransferFunction(0, 1);
    unsorted.transferFunction->opacity[1].x = -1;
    EXPECT_THROW(classify(v, unsorted), InputError);
}

TEST(ClassifyVolume, RealCtDataset) {
    const Volume ct = test::loadDataset("vtk_headsq_ct_64x64x93_uint16");  // spacing 3.2, 3.2, 1.5
    ClassifyParams params;
    params.transferFunction = test::datasetTransferFunction("vtk_headsq_ct.tf.json");
    const ClassifiedVolume c = classify(ct, params);
    ASSERT_EQ(c.sigma.size(), ct.values.size());
    EXPECT_DOUBLE_EQ(c.referenceStep, 1.5);
    std::size_t transparent = 0, flat = 0;
    for (std::size_t i = 0; i < c.sigma.size(); ++i) {
        ASSERT_TRUE(std::isfinite(c.sigma[i]) && c.sigma[i] >= 0);
        transparent += c.sigma[i] == 0;
        const auto& n = c.normal[i];
        const double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        if (len == 0) {
            ++flat;
        } else {
            EXPECT_NEAR(len, 1.0, 1e-6);
        }
    }
    // Air (below 500) is transparent, bone is not.
    EXPECT_GT(transparent, c.sigma.size() / 10);
    EXPECT_LT(transparent, c.sigma.size());
    EXPECT_LT(flat, c.sigma.size());
}

}  // namespace
}  // namespace vr
