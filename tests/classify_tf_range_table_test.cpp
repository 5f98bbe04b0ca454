// The range-extremum table over the tabulated transfer function (docs/ALGORITHMS.md section 9): random queries
// against brute force, a == b, the whole range, one entry, scalars between entries, transparent colour ignored.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "preprocess/classify/classify.h"
#include "preprocess/classify/tf_range_table.h"
#include "support/datasets.h"

namespace vr {
namespace {

// Extremes over entries first .. last by walking them.
TfExtremes bruteForce(const SampledTransferFunction& t, std::size_t first, std::size_t last) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    TfExtremes e{t.opacity[first], t.opacity[first], {kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
    for (std::size_t i = first; i <= last; ++i) {
        e.opacityMin = std::min(e.opacityMin, t.opacity[i]);
        e.opacityMax = std::max(e.opacityMax, t.opacity[i]);
        if (!(t.opacity[i] > 0)) continue;
        for (int c = 0; c < 3; ++c) {
            e.colourMin[c] = std::min(e.colourMin[c], t.colour[i][c]);
            e.colourMax[c] = std::max(e.colourMax[c], t.colour[i][c]);
        }
    }
    return e;
}

void expectEqual(const TfExtremes& a, const TfExtremes& b, const std::string& where) {
    EXPECT_EQ(a.opacityMin, b.opacityMin) << where;
    EXPECT_EQ(a.opacityMax, b.opacityMax) << where;
    EXPECT_EQ(a.colourMin, b.colourMin) << where;
    EXPECT_EQ(a.colourMax, b.colourMax) << where;
}

TransferFunction spiky() {
    TransferFunction tf;
    tf.opacity = {{0, 0}, {19, 0}, {20, 0.7}, {21, 0}, {40, 0}, {60, 0.3}, {200, 0.9}};
    tf.colour = {{0, 1, 0, 0}, {50, 0.2, 0.8, 0.4}, {255, 1, 1, 1}};
    return tf;
}

TEST(ClassifyTfRangeTable, RandomQueriesMatchBruteForce) {
    for (const std::size_t n : {1, 2, 3, 7, 64, 100, 4011}) {
        const SampledTransferFunction t =
            sampleTransferFunction(loadTransferFunction(test::datasetsDir() / "cranium_ct.tf.json"), -1024, 2986, n);
        const TfRangeTable table(t);
        ASSERT_EQ(table.size(), n);
        std::mt19937 rng{unsigned(n)};
        std::uniform_int_distribution<std::size_t> pick(0, n - 1);
        for (int q = 0; q < 500; ++q) {
            std::size_t a = pick(rng), b = pick(rng);
            if (a > b) std::swap(a, b);
            expectEqual(table.entries(a, b), bruteForce(t, a, b), std::to_string(n) + " entries, query " +
                                                                      std::to_string(a) + ".." + std::to_string(b));
        }
        for (std::size_t a = 0; a < n; a += 1 + n / 50) expectEqual(table.entries(a, a), bruteForce(t, a, a), "a == b");
        expectEqual(table.entries(0, n - 1), bruteForce(t, 0, n - 1), "whole range");
    }
}

TEST(ClassifyTfRangeTable, ScalarsBetweenEntriesReachBothNeighbours) {
    const SampledTransferFunction t = sampleTransferFunction(spiky(), 0, 255, 256);  // one entry per integer
    const TfRangeTable table(t);
    expectEqual(table.over(20, 20), bruteForce(t, 20, 20), "an entry alone");
    expectEqual(table.over(19.5, 19.5), bruteForce(t, 19, 20), "between two entries");
    expectEqual(table.over(10, 30), bruteForce(t, 10, 30), "integer interval");
    expectEqual(table.over(10.2, 29.9), bruteForce(t, 10, 30), "rounded outward");
    expectEqual(table.over(-50, 1e6), bruteForce(t, 0, 255), "clamped to the table");
    // The spike at 20 lies between two transparent values: never alike, whatever the threshold below its height.
    EXPECT_TRUE(table.alike(10, 10, 0));
    EXPECT_TRUE(table.alike(30, 30, 0));
    EXPECT_TRUE(table.alike(0, 19, 0)) << "transparent throughout: colour ignored";
    EXPECT_FALSE(table.alike(10, 30, 0));
    EXPECT_FALSE(table.alike(10, 30, 0.69));
    EXPECT_TRUE(table.alike(10, 30, 0.7)) << "the spread may equal T_o";
    EXPECT_FALSE(table.alike(19.5, 19.5, 0)) << "an interpolated scalar sees the spike";
}

TEST(ClassifyTfRangeTable, ColourCountsOnlyWhereOpaque) {
    TransferFunction tf;
    tf.opacity = {{0, 0}, {9, 0}, {10, 0.5}, {20, 0.5}};
    tf.colour = {{0, 1, 0, 0}, {9, 0, 1, 0}, {10, 0, 0, 1}, {20, 0, 0, 1}};
    const TfRangeTable table(sampleTransferFunction(tf, 0, 20, 21));
    EXPECT_TRUE(table.alike(0, 9, 0)) << "transparent red to green: colour unseen";
    EXPECT_TRUE(table.alike(10, 20, 0));
    EXPECT_FALSE(table.alike(9, 20, 0.49)) << "opacity 0 to 0.5";
    EXPECT_TRUE(table.alike(9, 20, 0.5)) << "the transparent entry's colour does not count";
}

TEST(ClassifyTfRangeTable, OneEntry) {
    TransferFunction tf;
    tf.opacity = {{0, 0.25}, {1, 0.25}};
    const TfRangeTable table(sampleTransferFunction(tf, 5, 5, 1));
    ASSERT_EQ(table.size(), 1u);
    const TfExtremes e = table.over(-1e9, 1e9);
    EXPECT_EQ(e.opacityMin, 0.25);
    EXPECT_EQ(e.opacityMax, 0.25);
    EXPECT_TRUE(table.alike(5, 5, 0));
}

TEST(ClassifyTfRangeTable, BuiltOnTheEntriesClassificationSamples) {
    // An integer volume is tabulated once per integer from its smallest to its largest value; classify() looks
    // every voxel up there, so the table's extremes at a voxel's value are that voxel's classification.
    Volume v;
    v.grid.dims = {4, 1, 1};
    v.sourceType = ScalarType::UInt8;
    v.values = {10, 19, 20, 30};
    ClassifyParams p;
    p.transferFunction = spiky();
    p.normals = false;
    const ClassifiedVolume c = classify(v, p);
    const TfRangeTable table(sampleForVolume(v, *p.transferFunction));
    EXPECT_EQ(table.size(), 21u);
    for (std::size_t i = 0; i < v.values.size(); ++i) {
        const TfExtremes e = table.over(v.values[i], v.values[i]);
        EXPECT_EQ(float(extinctionFromOpacity(e.opacityMax, c.referenceStep)), c.sigma[i]) << v.values[i];
        EXPECT_EQ(e.opacityMin, e.opacityMax);
    }
}

}  // namespace
}  // namespace vr
