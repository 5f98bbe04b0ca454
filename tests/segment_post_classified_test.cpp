// Regions for post-classified trilinear sampling (docs/ALGORITHMS.md section 9): the scalars that a region's
// interpolation footprints span classify alike within T_o, so a narrow peak of the transfer function between two
// transparent values is never inside one region; border voxels by footprint; nearest sampling unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <mutex>
#include <random>
#include <set>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/classify.h"
#include "preprocess/classify/tf_range_table.h"
#include "preprocess/segment/region_key.h"
#include "preprocess/segment/segment.h"
#include "support/datasets.h"

namespace vr {
namespace {

// Zero everywhere but a spike at 20; opaque from 60 up.
TransferFunction spikeAt20() {
    TransferFunction tf;
    tf.opacity = {{0, 0}, {19, 0}, {20, 0.7}, {21, 0}, {40, 0}, {60, 0.3}, {200, 0.9}};
    tf.colour = {{0, 1, 0, 0}, {60, 0.2, 0.8, 0.4}, {255, 1, 1, 1}};
    return tf;
}

Volume volumeOf(Vec3i dims, std::vector<float> values, ScalarType type = ScalarType::UInt8) {
    Volume v;
    v.grid.dims = dims;
    v.sourceType = type;
    v.values = std::move(values);
    return v;
}

struct Prepared {
    Volume volume;
    ClassifiedVolume classified;
    TfRangeTable spread;
    Regions segment(const SegmentationParams& p) const {
        return vr::segment(classified, p, ClassifiedScalars{volume.values, spread});
    }
};

Prepared prepared(Volume volume, const TransferFunction& tf, bool normals) {
    ClassifyParams p;
    p.transferFunction = tf;
    p.normals = normals;
    ClassifiedVolume c = classify(volume, p);
    TfRangeTable spread(sampleForVolume(volume, tf));
    return {std::move(volume), std::move(c), std::move(spread)};
}

std::vector<uint32_t> sizes(const Regions& r) {
    std::vector<uint32_t> s(r.count);
    for (uint32_t l : r.label) ++s[l];
    return s;
}

// The rule, checked by brute force: labels compact in first-voxel order; every region of more than one voxel
// spans (with its voxels' 3x3x3 footprints) a scalar interval that classifies alike within T_o, and, where
// normals are used, all its voxels and their 26 neighbours have the normal key of its first voxel.
void expectPostClassifiedRegions(const Prepared& v, const Regions& r, const SegmentationParams& p) {
    const Vec3i d = v.volume.grid.dims;
    uint32_t next = 0;
    for (uint32_t l : r.label) {
        ASSERT_LE(l, next) << "labels not in first-voxel order";
        if (l == next) ++next;
    }
    ASSERT_EQ(next, r.count);
    const std::vector<uint32_t> size = sizes(r);
    const RegionKeyer keyer(v.classified, p);
    std::vector<float> lo(r.count, 1e30f), hi(r.count, -1e30f);
    std::vector<std::size_t> first(r.count, SIZE_MAX);
    for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
            for (int x = 0; x < d.x; ++x) {
                const std::size_t i = linearIndex(d, x, y, z);
                const uint32_t l = r.label[i];
                if (size[l] == 1) continue;
                if (first[l] == SIZE_MAX) first[l] = i;
                for (int k = std::max(z - 1, 0); k <= std::min(z + 1, d.z - 1); ++k)
                    for (int j = std::max(y - 1, 0); j <= std::min(y + 1, d.y - 1); ++j)
                        for (int h = std::max(x - 1, 0); h <= std::min(x + 1, d.x - 1); ++h) {
                            const std::size_t u = linearIndex(d, h, j, k);
                            lo[l] = std::min(lo[l], v.volume.values[u]);
                            hi[l] = std::max(hi[l], v.volume.values[u]);
                            if (keyer.usesNormals()) {
                                ASSERT_EQ(keyer.normalKey(u), keyer.normalKey(first[l]))
                                    << "normals mix in the footprint of " << x << "," << y << "," << z;
                            }
                        }
            }
    for (uint32_t l = 0; l < r.count; ++l)
        if (size[l] > 1) {
            ASSERT_TRUE(v.spread.alike(lo[l], hi[l], p.opacityThreshold))
                << "region " << l << " spans scalars " << lo[l] << ".." << hi[l];
        }
}

TEST(SegmentPostClassified, APeakBetweenTwoValuesSeparatesThem) {
    // Voxels at 10 and 30, both transparent; interpolating between them crosses the spike at 20.
    // A float volume's table interpolates 65536 entries between 10 and 30: it sees the spike too.
    std::vector<float> values(8 * 4 * 4);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = i % 8 < 4 ? 10 : 30;
    for (const ScalarType type : {ScalarType::UInt8, ScalarType::Float32}) {
        SCOPED_TRACE(std::string(scalarTypeName(type)));
        const Prepared v = prepared(volumeOf({8, 4, 4}, values, type), spikeAt20(), false);
        SegmentationParams p{0, 0, false, true};
        const Regions trilinear = v.segment(p);
        expectPostClassifiedRegions(v, trilinear, p);
        for (std::size_t i = 0; i + 1 < values.size(); ++i)
            if (values[i] != values[i + 1] && i % 8 != 7) {
                EXPECT_FALSE(trilinear.same(i, i + 1)) << "10 and 30 adjacent share a region at voxel " << i;
            }
        // Nearest sampling never interpolates: both values are transparent, one region.
        p.trilinear = false;
        EXPECT_EQ(v.segment(p).count, 1u);
        EXPECT_EQ(segment(v.classified, p).count, 1u);
    }
}

TEST(SegmentPostClassified, BorderVoxelsAreThoseWhoseFootprintSpreads) {
    // x < 4: 10, x >= 4: 30. The footprints of x = 3 and x = 4 span the spike: regions of one voxel; x <= 2 and
    // x >= 5 each one region.
    const Vec3i d{9, 3, 3};
    std::vector<float> values(voxelCount(d));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = i % 9 < 4 ? 10 : 30;
    const Prepared v = prepared(volumeOf(d, values), spikeAt20(), true);
    for (const bool normals : {false, true}) {
        const SegmentationParams p{0, 0, normals, true};
        const Regions r = v.segment(p);
        expectPostClassifiedRegions(v, r, p);
        const std::vector<uint32_t> size = sizes(r);
        for (int z = 0; z < d.z; ++z)
            for (int y = 0; y < d.y; ++y)
                for (int x = 0; x < d.x; ++x) {
                    const std::size_t i = linearIndex(d, x, y, z);
                    EXPECT_EQ(size[r.label[i]] == 1, x == 3 || x == 4) << x << "," << y << "," << z;
                    EXPECT_EQ(r.same(i, linearIndex(d, 0, 0, 0)), x <= 2);
                    EXPECT_EQ(r.same(i, linearIndex(d, 8, 2, 2)), x >= 5);
                }
        EXPECT_EQ(r.count, 2u + 2 * 9);
    }
    // A threshold at the spike's height lets the footprint through: one region.
    EXPECT_EQ(v.segment({0.7, 0, false, true}).count, 1u);
}

TEST(SegmentPostClassified, NoisyAirIsOneRegionAtZeroThreshold) {
    // Every value from 0 to 18 is transparent (and the colour of transparent values is never seen).
    const Vec3i d{20, 17, 11};
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> noise(0, 18);
    std::vector<float> values(voxelCount(d));
    for (float& f : values) f = float(noise(rng));
    const Prepared v = prepared(volumeOf(d, values), spikeAt20(), true);
    for (const bool normals : {false, true}) {
        const Regions r = v.segment({0, 0, normals, true});
        EXPECT_EQ(r.count, 1u) << (normals ? "normals used" : "normals ignored");
    }
}

TEST(SegmentPostClassified, RandomVolumesKeepTheRule) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 6; ++trial) {
        const Vec3i d{5 + trial, 9 - trial, 4 + 2 * trial};
        std::uniform_real_distribution<double> u(0, 1);
        std::vector<float> values(voxelCount(d));
        const double base = 255 * u(rng);
        for (int z = 0; z < d.z; ++z)
            for (int y = 0; y < d.y; ++y)
                for (int x = 0; x < d.x; ++x)  // a ramp with noise: regions of every size
                    values[linearIndex(d, x, y, z)] =
                        float(std::round(std::clamp(base + 9 * x - 4 * y + 3 * z + 6 * u(rng), 0.0, 255.0)));
        const Prepared v = prepared(volumeOf(d, values), spikeAt20(), true);
        for (const double to : {0.0, 0.02, 0.1, 0.5})
            for (const double ta : {0.0, 10.0, 180.0})
                for (const bool normals : {false, true}) {
                    const SegmentationParams p{to, ta, normals, true};
                    const Regions r = v.segment(p);
                    SCOPED_TRACE("trial " + std::to_string(trial) + " T_o " + std::to_string(to) + " T_a " +
                                 std::to_string(ta) + (normals ? " normals" : ""));
                    expectPostClassifiedRegions(v, r, p);
                    EXPECT_EQ(v.segment(p).label, r.label) << "not deterministic";
                }
    }
}

Prepared shells() {
    return prepared(shellsPhantom({40, 36, 30}, {1, 1, 1.5}),
                    loadTransferFunction(test::datasetsDir() / "cranium_ct.tf.json"), true);
}

TEST(SegmentPostClassified, NearestSamplingKeepsTheKeyComponents) {
    const Prepared v = shells();
    for (const double to : {0.0, 0.02}) {
        const SegmentationParams p{to, 10, true, false};
        const Regions withScalars = v.segment(p), without = segment(v.classified, p);
        EXPECT_EQ(withScalars.count, without.count);
        EXPECT_EQ(withScalars.label, without.label);
    }
}

TEST(SegmentPostClassified, CtShellsKeepTheRule) {
    const Prepared v = shells();
    for (const double to : {0.0, 0.02})
        for (const double ta : {0.0, 10.0}) {
            const SegmentationParams p{to, ta, true, true};
            const Regions r = v.segment(p);
            SCOPED_TRACE("T_o " + std::to_string(to) + " T_a " + std::to_string(ta));
            expectPostClassifiedRegions(v, r, p);
            std::cout << "shells T_o " << to << " T_a " << ta << ": " << r.count << " post-classified regions, "
                      << segment(v.classified, p).count << " by classified voxels\n";
        }
}

TEST(SegmentPostClassified, ScalarsOfAnotherSizeAreAnInputError) {
    const Prepared v = prepared(volumeOf({4, 1, 1}, {10, 10, 30, 30}), spikeAt20(), false);
    const std::vector<float> tooFew{10, 10};
    EXPECT_THROW(segment(v.classified, {0, 0, false, true}, ClassifiedScalars{tooFew, v.spread}), InputError);
    EXPECT_THROW(v.segment({-1, 0, false, true}), InputError);
}

// What segmentation tells a progress bar: fractions in [0, 1], from every step (the footprints, the normal classes
// in runs of 2^20 voxels, the growth per 2^20 voxels labelled), ending at 1; both samplings.
TEST(SegmentPostClassified, ReportsItsProgress) {
    const Vec3i dims{160, 128, 110};  // 2.25 M voxels: more than one run of 2^20
    std::vector<float> values(voxelCount(dims));
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> noise(0, 8);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float((i / 4000 % 3) * 60 + noise(rng));
    const Prepared v = prepared(volumeOf(dims, values), spikeAt20(), true);
    for (bool trilinear : {true, false}) {
        SCOPED_TRACE(trilinear ? "trilinear" : "nearest");
        std::mutex mutex;
        std::vector<double> heard;
        const Progress progress = [&](double f) {
            std::lock_guard lock(mutex);
            heard.push_back(f);
        };
        Regions regions;
        segment(v.classified, SegmentationParams{0.05, 10, true, trilinear},
                ClassifiedScalars{v.volume.values, v.spread}, regions, progress);
        ASSERT_FALSE(heard.empty());
        for (double f : heard) EXPECT_TRUE(f >= 0 && f <= 1) << f;
        EXPECT_EQ(heard.back(), 1.0);
        if (trilinear) EXPECT_GE(std::set<double>(heard.begin(), heard.end()).size(), 6u);
    }
}

}  // namespace
}  // namespace vr
