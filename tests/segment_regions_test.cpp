// Homogeneous regions: a partition with bounded variation (checked exhaustively on small volumes and on real CT),
// exact runs at T = 0, trilinear border regions, bad thresholds.
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <numbers>
#include <random>

#include "core/errors.h"
#include "preprocess/classify/classify.h"
#include "preprocess/load/load_volume.h"
#include "preprocess/segment/region_key.h"
#include "preprocess/segment/segment.h"
#include "support/load_dataset.h"
#include "support/volumes.h"

namespace vr {
namespace {

using Normal = std::array<float, 3>;

double angleDeg(const Normal& a, const Normal& b) {
    const double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
    const double la = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
    const double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
    return std::acos(std::clamp(d / (la * lb), -1.0, 1.0)) * 180 / std::numbers::pi;
}
bool isFlat(const Normal& n) { return n[0] == 0 && n[1] == 0 && n[2] == 0; }

ClassifiedVolume emptyClassified(Vec3i dims, bool normals) {
    ClassifiedVolume c;
    c.grid.dims = dims;
    c.sigma.assign(c.grid.voxels(), 0.f);
    c.colour.assign(c.grid.voxels(), {1, 1, 1});
    if (normals) c.normal.assign(c.grid.voxels(), {0, 0, 0});
    return c;
}

// A smooth random scalar field (Gaussian blobs plus noise) classified with a coloured TF and normals.
ClassifiedVolume smoothClassified(Vec3i dims, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    struct Blob { Vec3d c; double r, h; };
    std::vector<Blob> blobs;
    for (int b = 0; b < 5; ++b)
        blobs.push_back({Vec3d{u(rng) * dims.x, u(rng) * dims.y, u(rng) * dims.z}, 2 + 5 * u(rng), 60 + 140 * u(rng)});
    const Volume v = test::volumeOf(dims, {1, 1.2, 1.5}, ScalarType::UInt8, [&](int x, int y, int z) {
        double f = 4 * u(rng);
        for (const Blob& b : blobs) {
            const Vec3d d = Vec3d{double(x), double(y), double(z)} - b.c;
            f += b.h * std::exp(-dot(d, d) / (b.r * b.r));
        }
        return std::round(std::min(f, 255.0));
    });
    ClassifyParams params;
    TransferFunction tf;
    tf.opacity = {{0, 0}, {20, 0}, {120, 0.4}, {255, 0.9}};
    tf.colour = {{0, 0, 0, 0}, {100, 0.9, 0.5, 0.3}, {255, 1, 1, 1}};
    params.transferFunction = tf;
    return classify(v, params);
}

// Labels 0..count-1, each used, numbered in the order of their first voxel.
void expectCompactFirstVoxelOrder(const Regions& r, Vec3i dims) {
    ASSERT_EQ(r.dims, dims);
    ASSERT_EQ(r.label.size(), voxelCount(dims));
    uint32_t next = 0;
    for (uint32_t l : r.label) {
        ASSERT_LE(l, next) << "labels not in first-voxel order";
        if (l == next) ++next;
    }
    EXPECT_EQ(next, r.count);
}

// The requirement: every voxel within T_o / T_a of its region's representative (the first voxel). Opacity and
// colour are checked as a spread (max - min < T_o), which is what the binning guarantees between ANY two voxels.
void expectBoundedVariation(const ClassifiedVolume& c, const Regions& r, const SegmentationParams& p) {
    const bool normals = p.useNormals && c.hasNormals();
    std::vector<std::size_t> representative(r.count, SIZE_MAX);
    std::vector<std::array<double, 8>> range(r.count);  // min/max of opacity, r, g, b
    for (std::size_t i = 0; i < r.label.size(); ++i) {
        const uint32_t l = r.label[i];
        const double values[4] = {c.opacity(i), c.colour[i][0], c.colour[i][1], c.colour[i][2]};
        if (representative[l] == SIZE_MAX) {
            representative[l] = i;
            for (int k = 0; k < 4; ++k) range[l][2 * k] = range[l][2 * k + 1] = values[k];
            continue;
        }
        const std::size_t rep = representative[l];
        ASSERT_EQ(c.sigma[i] == 0, c.sigma[rep] == 0) << "transparent and opaque voxels share region " << l;
        if (c.sigma[i] == 0) continue;  // transparent: colour and normal contribute nothing
        for (int k = 0; k < 4; ++k) {
            range[l][2 * k] = std::min(range[l][2 * k], values[k]);
            range[l][2 * k + 1] = std::max(range[l][2 * k + 1], values[k]);
            if (p.opacityThreshold == 0) {
                ASSERT_EQ(values[k], range[l][2 * k]) << "T_o = 0 needs identical voxels";
            }
            ASSERT_LE(range[l][2 * k + 1] - range[l][2 * k], p.opacityThreshold + 1e-12)
                << (k == 0 ? "opacity" : "colour") << " spread in region " << l;
        }
        if (normals) {
            ASSERT_EQ(isFlat(c.normal[i]), isFlat(c.normal[rep])) << "flat and non-flat voxels share region " << l;
            if (!isFlat(c.normal[i])) {
                if (p.angleThresholdDeg == 0) {
                    ASSERT_EQ(c.normal[i], c.normal[rep]);
                }
                ASSERT_LE(angleDeg(c.normal[i], c.normal[rep]), p.angleThresholdDeg + 1e-3) << "region " << l;
            }
        }
    }
}

// What the cube-map cells guarantee, stronger than the requirement: normals within T_a of each other pairwise.
void expectPairwiseAngles(const ClassifiedVolume& c, const Regions& r, double angleDeg_) {
    std::vector<std::vector<std::size_t>> members(r.count);
    for (std::size_t i = 0; i < r.label.size(); ++i)
        if (c.sigma[i] > 0 && !isFlat(c.normal[i])) members[r.label[i]].push_back(i);
    for (const auto& m : members)
        for (std::size_t a = 0; a < m.size(); ++a)
            for (std::size_t b = a + 1; b < m.size(); ++b)
                ASSERT_LE(angleDeg(c.normal[m[a]], c.normal[m[b]]), angleDeg_ + 1e-3);
}

// Reference labelling: breadth-first flood fill over a pairwise predicate, regions numbered by first voxel.
Regions floodFill(Vec3i dims, const std::function<bool(std::size_t, std::size_t)>& same) {
    Regions r;
    r.dims = dims;
    r.label.assign(voxelCount(dims), UINT32_MAX);
    const std::size_t strides[3] = {1, std::size_t(dims.x), std::size_t(dims.x) * dims.y};
    for (std::size_t seed = 0; seed < r.label.size(); ++seed) {
        if (r.label[seed] != UINT32_MAX) continue;
        std::deque<std::size_t> queue{seed};
        r.label[seed] = r.count;
        while (!queue.empty()) {
            const std::size_t i = queue.front();
            queue.pop_front();
            const int v[3] = {int(i % dims.x), int(i / dims.x % dims.y), int(i / strides[2])};
            for (int a = 0; a < 3; ++a)
                for (int s : {-1, 1}) {
                    const int w = v[a] + s;
                    if (w < 0 || w >= dims[a]) continue;
                    const std::size_t j = s < 0 ? i - strides[a] : i + strides[a];
                    if (r.label[j] == UINT32_MAX && same(i, j)) {
                        r.label[j] = r.count;
                        queue.push_back(j);
                    }
                }
        }
        ++r.count;
    }
    return r;
}

// Bit-identical classified voxels (transparent ones are identical whatever their colour and normal).
bool identical(const ClassifiedVolume& c, bool normals, std::size_t a, std::size_t b) {
    if (c.sigma[a] == 0 || c.sigma[b] == 0) return c.sigma[a] == 0 && c.sigma[b] == 0;
    return c.sigma[a] == c.sigma[b] && c.colour[a] == c.colour[b] && (!normals || c.normal[a] == c.normal[b]);
}

// For trilinear regions: a voxel of a region of more than one voxel has its whole 26-neighbourhood in its
// original (non-trilinear) region.
void expectFootprintsInsideRegions(const Regions& plain, const Regions& trilinear) {
    const Vec3i d = plain.dims;
    std::vector<uint32_t> size(trilinear.count);
    for (uint32_t l : trilinear.label) ++size[l];
    std::size_t borders = 0;
    for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
            for (int x = 0; x < d.x; ++x) {
                const std::size_t i = linearIndex(d, x, y, z);
                bool mixed = false;
                for (int k = std::max(z - 1, 0); k <= std::min(z + 1, d.z - 1); ++k)
                    for (int j = std::max(y - 1, 0); j <= std::min(y + 1, d.y - 1); ++j)
                        for (int h = std::max(x - 1, 0); h <= std::min(x + 1, d.x - 1); ++h)
                            mixed |= plain.label[linearIndex(d, h, j, k)] != plain.label[i];
                if (mixed) {
                    ++borders;
                    ASSERT_EQ(size[trilinear.label[i]], 1u) << "border voxel " << x << "," << y << "," << z;
                } else {
                    ASSERT_GE(size[trilinear.label[i]], 1u);
                }
            }
    // Every non-border voxel keeps its plain region's company: same plain region <=> same trilinear region.
    std::map<uint32_t, uint32_t> toPlain;
    for (std::size_t i = 0; i < plain.label.size(); ++i) {
        auto [it, added] = toPlain.emplace(trilinear.label[i], plain.label[i]);
        ASSERT_EQ(it->second, plain.label[i]) << "a trilinear region spans two plain regions";
    }
    std::size_t singletons = 0;
    for (uint32_t s : size) singletons += s == 1;
    EXPECT_GE(singletons, borders);
}

TEST(SegmentRegions, BoundedVariationOnRandomVolumes) {
    const Vec3i dims{21, 17, 15};
    for (unsigned seed : {1u, 2u, 3u}) {
        const ClassifiedVolume c = smoothClassified(dims, seed);
        for (auto [to, ta] : {std::pair{0.0, 0.0}, {0.01, 3.0}, {0.05, 10.0}, {0.1, 20.0}, {0.3, 60.0}, {1.0, 180.0}})
            for (bool useNormals : {true, false}) {
                SCOPED_TRACE(testing::Message() << "seed " << seed << " T_o " << to << " T_a " << ta << " normals "
                                                << useNormals);
                SegmentationParams p;
                p.opacityThreshold = to;
                p.angleThresholdDeg = ta;
                p.useNormals = useNormals;
                const Regions plain = segment(c, p);
                expectCompactFirstVoxelOrder(plain, dims);
                expectBoundedVariation(c, plain, p);
                if (useNormals) expectPairwiseAngles(c, plain, ta);
                // The labelling is exactly the connected components of equal keys.
                const RegionKeyer key(c, p);
                EXPECT_EQ(plain.label, floodFill(dims, [&](auto a, auto b) { return key(a) == key(b); }).label);
                p.trilinear = true;
                const Regions trilinear = segment(c, p);
                expectCompactFirstVoxelOrder(trilinear, dims);
                expectBoundedVariation(c, trilinear, p);
                expectFootprintsInsideRegions(plain, trilinear);
            }
    }
}

// Voxels drawn from a few classified values, so that runs, corners and seams of equal keys abound.
ClassifiedVolume patchyClassified(Vec3i dims, unsigned seed, int values) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> pick(0, values - 1);
    ClassifiedVolume c = emptyClassified(dims, true);
    for (std::size_t i = 0; i < c.sigma.size(); ++i) {
        const int v = pick(rng);
        c.sigma[i] = v == 0 ? 0.f : 0.1f * float(v);
        c.colour[i] = {0.2f * float(v % 3), 0.5f, 1.f};
        c.normal[i] = v % 2 ? Normal{0, 0, 1} : Normal{0.6f, 0.8f, 0};
    }
    return c;
}

TEST(SegmentRegions, LabelsAreTheComponentsOfEqualKeysOnEveryShape) {
    for (Vec3i dims : {Vec3i{1, 1, 13}, Vec3i{1, 7, 9}, Vec3i{8, 1, 5}, Vec3i{6, 5, 1}, Vec3i{33, 2, 3},
                       Vec3i{9, 9, 9}, Vec3i{2, 40, 2}})
        for (int values : {2, 3, 6}) {
            SCOPED_TRACE(testing::Message() << dims.x << "x" << dims.y << "x" << dims.z << ", " << values);
            const ClassifiedVolume c = patchyClassified(dims, unsigned(dims.x * 7 + values), values);
            SegmentationParams p{0.05, 10, true, false};
            const RegionKeyer key(c, p);
            const Regions plain = segment(c, p);
            expectCompactFirstVoxelOrder(plain, dims);
            EXPECT_EQ(plain.label, floodFill(dims, [&](auto a, auto b) { return key(a) == key(b); }).label);
            p.trilinear = true;
            const Regions trilinear = segment(c, p);
            expectCompactFirstVoxelOrder(trilinear, dims);
            expectFootprintsInsideRegions(plain, trilinear);
        }
}

TEST(SegmentRegions, LabelsAreTheComponentsOfEqualKeysAcrossSlabs) {
    // Enough slices for every thread's slabs of slices: components span slabs and are joined at their seams.
    const Vec3i dims{70, 50, 41};
    for (int values : {2, 5}) {
        const ClassifiedVolume c = patchyClassified(dims, unsigned(values), values);
        const SegmentationParams p{0.05, 10, true, false};
        const RegionKeyer key(c, p);
        const Regions plain = segment(c, p);
        expectCompactFirstVoxelOrder(plain, dims);
        EXPECT_EQ(plain.label, floodFill(dims, [&](auto a, auto b) { return key(a) == key(b); }).label);
    }
}

TEST(SegmentRegions, IntoUsedRegionsEqualsFresh) {
    Regions reused = segment(patchyClassified({9, 8, 7}, 1, 3), SegmentationParams{});
    for (Vec3i dims : {Vec3i{4, 6, 5}, Vec3i{9, 8, 7}, Vec3i{9, 8, 7}})
        for (bool trilinear : {false, true}) {
            const ClassifiedVolume c = patchyClassified(dims, unsigned(dims.x + trilinear), 4);
            const SegmentationParams p{0.05, 10, true, trilinear};
            segment(c, p, reused);
            const Regions fresh = segment(c, p);
            EXPECT_EQ(reused.dims, fresh.dims);
            EXPECT_EQ(reused.count, fresh.count);
            EXPECT_EQ(reused.label, fresh.label);
        }
}

TEST(SegmentRegions, KeysOfARunEqualSingleKeys) {
    // Many distinct (sigma, colour) pairs, more than the run's cache holds, with repeats far apart.
    const Vec3i dims{50, 40, 10};
    ClassifiedVolume c = emptyClassified(dims, true);
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> pick(0, 3000);
    std::uniform_real_distribution<float> unit(-1, 1);
    for (std::size_t i = 0; i < c.sigma.size(); ++i) {
        const int v = pick(rng);
        c.sigma[i] = v % 7 == 0 ? 0.f : float(v) * 1e-3f;
        c.colour[i] = {float(v % 11) / 10, float(v % 13) / 12, float(v % 17) / 16};
        c.normal[i] = {unit(rng), unit(rng), unit(rng)};
    }
    for (SegmentationParams p : {SegmentationParams{0, 0, true, false}, SegmentationParams{0.05, 10, true, false},
                                 SegmentationParams{0.2, 0, false, false}}) {
        const RegionKeyer key(c, p);
        std::vector<RegionKey> run(c.sigma.size() - 5);
        key.keys(5, run.size(), run.data());
        for (std::size_t j = 0; j < run.size(); ++j) ASSERT_EQ(run[j], key(5 + j)) << j;
        // Packed keys (binned thresholds only) are equal exactly where the keys are.
        EXPECT_EQ(key.packs(), p.opacityThreshold > 0);
        if (!key.packs()) continue;
        std::vector<PackedKey> packed(run.size());
        key.keys(5, packed.size(), packed.data());
        std::uniform_int_distribution<std::size_t> any(0, run.size() - 1);
        for (int k = 0; k < 20000; ++k) {
            const std::size_t a = any(rng), b = k % 2 ? any(rng) : (a + 1) % run.size();
            ASSERT_EQ(packed[a] == packed[b], run[a] == run[b]) << a << " " << b;
        }
    }
    // Coarse thresholds pack, bit-exact ones and bins too fine for 64 bits do not.
    EXPECT_TRUE(RegionKeyer(c, {1.0, 180, true, false}).packs());
    EXPECT_FALSE(RegionKeyer(c, {0.05, 0, true, false}).packs());
    EXPECT_FALSE(RegionKeyer(c, {1e-6, 10, true, false}).packs());
}

TEST(SegmentRegions, SmoothRampIsNotOneRegion) {
    // Opacity rises by 0.01 per voxel: every neighbour pair is similar at T_o = 0.05, the ends are not.
    const Vec3i dims{101, 3, 2};
    ClassifiedVolume c = emptyClassified(dims, false);
    for (std::size_t i = 0; i < c.sigma.size(); ++i) c.sigma[i] = float(extinctionFromOpacity((i % 101) / 100.0, 1));
    for (double to : {0.05, 0.2}) {
        SegmentationParams p;
        p.opacityThreshold = to;
        const Regions r = segment(c, p);
        expectCompactFirstVoxelOrder(r, dims);
        expectBoundedVariation(c, r, p);
        EXPECT_GE(r.count, uint32_t(std::floor(1 / to)));
        EXPECT_LE(r.count, uint32_t(std::ceil(1 / to)) + 2);  // bins, plus transparent, plus alpha = 1
    }
}

TEST(SegmentRegions, ZeroThresholdsGiveRunsOfIdenticalVoxels) {
    const Vec3i dims{13, 11, 10};
    std::mt19937 rng(7);
    ClassifiedVolume c = emptyClassified(dims, true);
    const float sigmas[3] = {0.f, 0.5f, 2.f};
    const Normal normals[3] = {{0, 0, 0}, {1, 0, 0}, {0, 0.6f, 0.8f}};
    // Blocks of 2x2x2 with a random value each, then a few random voxels changed: runs of several sizes.
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                std::mt19937 block(unsigned((x / 2) + 100 * (y / 2) + 10000 * (z / 2)));
                const std::size_t i = linearIndex(dims, x, y, z);
                c.sigma[i] = sigmas[block() % 3];
                c.colour[i] = {float(block() % 2), 0.5f, 1.f};
                c.normal[i] = normals[block() % 3];
                if (rng() % 10 == 0) c.colour[i][1] = 0.25f;  // differs only where opaque
            }
    for (bool useNormals : {true, false}) {
        SegmentationParams p;
        p.useNormals = useNormals;
        const Regions r = segment(c, p);
        expectCompactFirstVoxelOrder(r, dims);
        expectBoundedVariation(c, r, p);
        EXPECT_EQ(r.label, floodFill(dims, [&](auto a, auto b) { return identical(c, useNormals, a, b); }).label);
        EXPECT_GT(r.count, 20u);
    }
}

TEST(SegmentRegions, TransparentVoxelsIgnoreColourAndNormals) {
    const Vec3i dims{8, 8, 8};
    ClassifiedVolume c = emptyClassified(dims, true);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1, 1);
    for (std::size_t i = 0; i < c.sigma.size(); ++i) {
        c.colour[i] = {std::abs(u(rng)), std::abs(u(rng)), std::abs(u(rng))};
        c.normal[i] = {u(rng), u(rng), u(rng)};
    }
    EXPECT_EQ(segment(c, SegmentationParams{}).count, 1u);
    // One opaque voxel inside: a region of its own, the air around it stays one region.
    c.sigma[linearIndex(dims, 4, 4, 4)] = 1.f;
    EXPECT_EQ(segment(c, SegmentationParams{0.5, 90, true, false}).count, 2u);
}

TEST(SegmentRegions, FlatNormalsAreSimilarOnlyToFlatNormals) {
    const Vec3i dims{3, 1, 1};
    ClassifiedVolume c = emptyClassified(dims, true);
    c.sigma = {1.f, 1.f, 1.f};
    c.normal = {Normal{0, 0, 0}, Normal{1, 0, 0}, Normal{-1, 0, 0}};
    SegmentationParams p{0.1, 180, true, false};
    EXPECT_EQ(segment(c, p).count, 2u);  // opposite normals are within 180 degrees, flat is apart
    p.angleThresholdDeg = 90;
    EXPECT_EQ(segment(c, p).count, 3u);
    p.useNormals = false;
    EXPECT_EQ(segment(c, p).count, 1u);
    c.normal.clear();  // a classification without normals
    p.useNormals = true;
    EXPECT_EQ(segment(c, p).count, 1u);
}

TEST(SegmentRegions, SmallerThresholdsGiveMoreRegions) {
    const Vec3i dims{24, 24, 20};
    const ClassifiedVolume c = smoothClassified(dims, 11);
    // Halving T_o splits every bin in two, so the partition refines and the count cannot fall.
    uint32_t previous = 0;
    for (double to : {0.8, 0.4, 0.2, 0.1, 0.05, 0.025}) {
        const uint32_t count = segment(c, SegmentationParams{to, 0, false, false}).count;
        EXPECT_GE(count, previous) << to;
        previous = count;
    }
    EXPECT_GT(previous, segment(c, SegmentationParams{0.8, 0, false, false}).count);
    EXPECT_GE(segment(c, SegmentationParams{0, 0, false, false}).count, previous);
    // Angles on a sphere (normals point outward): finer cones, more regions.
    ClassifiedVolume sphere = emptyClassified({24, 24, 24}, true);
    for (int z = 0; z < 24; ++z)
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 24; ++x) {
                const Vec3d d = Vec3d{x - 11.5, y - 11.5, z - 11.5};
                const std::size_t i = linearIndex(sphere.grid.dims, x, y, z);
                sphere.sigma[i] = 1.f;
                const Vec3d n = normalize(d);
                sphere.normal[i] = {float(n.x), float(n.y), float(n.z)};
            }
    uint32_t coarse = 0;
    for (double ta : {120.0, 45.0, 20.0, 10.0, 5.0}) {
        SegmentationParams p{0.1, ta, true, false};
        const Regions r = segment(sphere, p);
        expectBoundedVariation(sphere, r, p);
        EXPECT_GT(r.count, coarse) << ta;
        coarse = r.count;
    }
}

TEST(SegmentRegions, CubeMapCellsHaveBoundedDiameter) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> u(0, 1);
    const auto unit = [](double x, double y, double z) {
        const double l = std::sqrt(x * x + y * y + z * z);
        return Normal{float(x / l), float(y / l), float(z / l)};
    };
    for (double ta : {3.0, 10.0, 25.0, 60.0, 110.0, 179.0}) {
        const int k = cubeMapCellsPerEdge(ta);
        ASSERT_GE(k, 1);
        // Many directions per cell: a window of about 8 x 8 cells at a face centre (where cells span the widest
        // angle) and at a cube corner, and directions all over the sphere, on every face and sign.
        const double window = std::min(1.0, 16.0 / k);
        std::vector<Normal> directions;
        for (int i = 0; i < 3000; ++i) {
            const double a = window * (2 * u(rng) - 1), b = window * (2 * u(rng) - 1);
            directions.push_back(unit(a, b, 1));
            directions.push_back(unit(1 - window * u(rng), -1 + window * u(rng), -1));
            const int axis = i % 3;
            Normal n = unit(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
            if (i % 2) n[axis] = -n[axis];
            directions.push_back(n);
        }
        for (float sx : {-1.f, 1.f})
            for (float sy : {-1.f, 1.f})
                for (float sz : {-1.f, 1.f}) directions.push_back(unit(sx, sy, sz));
        std::map<uint32_t, std::vector<Normal>> cells;
        for (const Normal& n : directions) {
            const uint32_t cell = cubeMapCell(n, k);
            ASSERT_LT(cell, uint32_t(6 * k * k));
            cells[cell].push_back(n);
        }
        double widest = 0;
        for (const auto& [cell, members] : cells)
            for (std::size_t i = 0; i < members.size(); ++i)
                for (std::size_t j = i + 1; j < members.size(); ++j)
                    widest = std::max(widest, angleDeg(members[i], members[j]));
        EXPECT_LE(widest, ta + 1e-4) << ta;
        EXPECT_GT(widest, ta / 4) << "cells much finer than needed at " << ta;
    }
    EXPECT_EQ(cubeMapCellsPerEdge(180), 0);
    EXPECT_EQ(cubeMapCell({0.3f, -0.2f, 0.9f}, 0), 0u);
}

TEST(SegmentRegions, TrilinearBorderVoxelsAreRegionsOfTheirOwn) {
    // Two slabs: transparent x < 5, opaque x >= 5. Border voxels: x = 4 and x = 5 (their footprints straddle).
    const Vec3i dims{10, 4, 3};
    ClassifiedVolume c = emptyClassified(dims, false);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 5; x < dims.x; ++x) c.sigma[linearIndex(dims, x, y, z)] = 1.f;
    SegmentationParams p;
    EXPECT_EQ(segment(c, p).count, 2u);
    p.trilinear = true;
    const Regions r = segment(c, p);
    expectCompactFirstVoxelOrder(r, dims);
    EXPECT_EQ(r.count, 2u + 2u * dims.y * dims.z);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y) {
            EXPECT_EQ(r.label[linearIndex(dims, 0, y, z)], r.label[0]);
            EXPECT_EQ(r.label[linearIndex(dims, 9, y, z)], r.label[9]);
            EXPECT_NE(r.label[linearIndex(dims, 4, y, z)], r.label[linearIndex(dims, 3, y, z)]);
            EXPECT_NE(r.label[linearIndex(dims, 5, y, z)], r.label[linearIndex(dims, 6, y, z)]);
        }
    // A region made only of border voxels disappears rather than leaving a gap in the labels.
    ClassifiedVolume thin = emptyClassified({5, 5, 5}, false);
    thin.sigma[linearIndex(thin.grid.dims, 2, 2, 2)] = 1.f;
    const Regions t = segment(thin, p);
    expectCompactFirstVoxelOrder(t, thin.grid.dims);
    EXPECT_EQ(t.count, 1u + 27u);
}

TEST(SegmentRegions, BadInputIsAnInputError) {
    const ClassifiedVolume c = emptyClassified({2, 2, 2}, true);
    for (double bad : {-0.01, std::nan("")}) {
        EXPECT_THROW(segment(c, SegmentationParams{bad, 1, true, false}), InputError);
        EXPECT_THROW(segment(c, SegmentationParams{0.1, bad, true, false}), InputError);
    }
    try {
        segment(c, SegmentationParams{-1, 0, true, false});
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("opacity threshold"), std::string::npos) << e.what();
    }
    ClassifiedVolume broken = c;
    broken.colour.pop_back();
    EXPECT_THROW(segment(broken, SegmentationParams{}), InputError);
    broken = c;
    broken.normal.resize(3);
    EXPECT_THROW(segment(broken, SegmentationParams{}), InputError);
}

TEST(SegmentRegionsOnDatasets, HeadCtAtSeveralThresholds) {
    const Volume ct = test::loadDataset("vtk_headsq_ct_64x64x93_uint16");
    ClassifyParams cp;
    cp.transferFunction = test::datasetTransferFunction("vtk_headsq_ct.tf.json");
    const ClassifiedVolume c = classify(ct, cp);
    uint32_t previous = 0;
    for (auto [to, ta] : {std::pair{0.5, 90.0}, {0.1, 20.0}, {0.02, 3.0}, {0.0, 0.0}}) {
        SegmentationParams p{to, ta, true, false};
        const Regions r = segment(c, p);
        expectCompactFirstVoxelOrder(r, ct.grid.dims);
        expectBoundedVariation(c, r, p);
        EXPECT_GT(r.count, previous);
        previous = r.count;
        std::cout << "headsq T_o " << to << " T_a " << ta << ": " << r.count << " regions\n";
    }
    // T = 0: the transparent air is one big region.
    const Regions exact = segment(c, SegmentationParams{});
    std::vector<std::size_t> size(exact.count);
    for (uint32_t l : exact.label) ++size[l];
    EXPECT_GT(*std::max_element(size.begin(), size.end()), c.sigma.size() / 10);
}

TEST(SegmentRegionsOnDatasets, CraniumCtClassifyAndSegment) {
    const Volume ct = test::loadDataset("cranium_ct_256x256x108_int16");
    ClassifyParams cp;
    cp.transferFunction = test::datasetTransferFunction("cranium_ct.tf.json");
    using Clock = std::chrono::steady_clock;
    // Informative only (speed is asserted in benchmarks): wall and process CPU time (all threads).
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();
    const ClassifiedVolume c = classify(ct, cp);
    const auto t1 = Clock::now();
    const std::clock_t c1 = std::clock();
    SegmentationParams p{0.01, 3, true, false};
    const Regions r = segment(c, p);
    const auto t2 = Clock::now();
    const std::clock_t c2 = std::clock();
    p.trilinear = true;
    const Regions trilinear = segment(c, p);
    const auto t3 = Clock::now();
    const std::clock_t c3 = std::clock();
    const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    const auto cpu = [](std::clock_t a, std::clock_t b) { return 1000.0 * double(b - a) / CLOCKS_PER_SEC; };
    std::cout << "cranium 256x256x108 wall (cpu) ms: classify " << ms(t0, t1) << " (" << cpu(c0, c1)
              << "), segment (0.01, 3 deg) " << ms(t1, t2) << " (" << cpu(c1, c2) << ") -> " << r.count
              << " regions; trilinear " << ms(t2, t3) << " (" << cpu(c2, c3) << ") -> " << trilinear.count
              << " regions\n";
    expectCompactFirstVoxelOrder(r, ct.grid.dims);
    p.trilinear = false;
    expectBoundedVariation(c, r, p);
    expectCompactFirstVoxelOrder(trilinear, ct.grid.dims);
    EXPECT_LT(r.count, c.sigma.size() / 2);
}

}  // namespace
}  // namespace vr
