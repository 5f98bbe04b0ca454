// Ray setup and leap counts on hand cases (docs/ALGORITHMS.md sections 1 and 5, render/ray_setup.h): entry and
// exit, the lattice and its voxels, and how many samples a leap through a PC ball or an octant box covers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/ray_setup.h"

namespace vr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(RenderRaySetup, EntryAndExitForMissingGrazingAndInsideRays) {
    const Vec3i dims{4, 4, 4};
    // Straight through along x.
    RayInterval iv = intersectGrid({{-1, 1.5, 1.5}, {1, 0, 0}}, dims);
    EXPECT_EQ(iv.tEntry, 1.0);
    EXPECT_EQ(iv.tExit, 5.0);
    // Misses: parallel outside a slab, pointing away, passing beside.
    EXPECT_TRUE(intersectGrid({{-1, 5, 1.5}, {1, 0, 0}}, dims).empty());
    EXPECT_TRUE(intersectGrid({{-1, 1.5, 1.5}, {-1, 0, 0}}, dims).empty());
    EXPECT_TRUE(intersectGrid({{-1, 6, 1.5}, {0.6, 0.8, 0}}, dims).empty());
    // Grazing a face: the near faces belong to the volume (voxel 0), the far faces do not (cells are [v, v+1)).
    iv = intersectGrid({{-1, 0, 0}, {1, 0, 0}}, dims);
    EXPECT_EQ(iv.tEntry, 1.0);
    EXPECT_EQ(iv.tExit, 5.0);
    EXPECT_TRUE(intersectGrid({{-1, 4, 1}, {1, 0, 0}}, dims).empty());
    EXPECT_TRUE(intersectGrid({{-1, 1, 4}, {1, 0, 0}}, dims).empty());
    // Touching only an edge: an empty interval, not a NaN.
    const Vec3d diag = normalize(Vec3d{1, 1, 0});
    iv = intersectGrid({{-1, 3, 2}, diag}, dims);
    EXPECT_TRUE(iv.empty());
    EXPECT_FALSE(std::isnan(iv.tEntry));
    // Through an edge into the volume: enters at the edge.
    iv = intersectGrid({{-1, -1, 2}, diag}, dims);
    EXPECT_NEAR(iv.tEntry, std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(iv.tExit, 5 * std::sqrt(2.0), 1e-14);
    // Starting inside: tEntry clamps to 0.
    iv = intersectGrid({{2, 2, 2}, {0, 0, 1}}, dims);
    EXPECT_EQ(iv.tEntry, 0.0);
    EXPECT_EQ(iv.tExit, 2.0);
    iv = intersectGrid({{2, 2, 2}, {0, 0, -1}}, dims);
    EXPECT_EQ(iv.tEntry, 0.0);
    EXPECT_EQ(iv.tExit, 2.0);
    // Negative zero counts as zero (an exactly axis-aligned view), and as a positive octant.
    iv = intersectGrid({{1.5, 1.5, 9}, {-0.0, -0.0, -1}}, dims);
    EXPECT_EQ(iv.tEntry, 5.0);
    EXPECT_EQ(iv.tExit, 9.0);
    EXPECT_EQ(rayOctant({{0, 0, 0}, {-0.0, -0.0, -1}}), 4);
    EXPECT_EQ(rayOctant({{0, 0, 0}, {-1, 2, -0.5}}), 5);
}

TEST(RenderRaySetup, GridRayKeepsWorldDistance) {
    GridGeometry g;
    g.dims = {4, 4, 4};
    g.spacing = {2, 2, 0.5};
    g.origin = {1, 1, 1};
    const GridRay r = toGridRay({{-9, 4, 2}, {1, 0, 0}}, g);
    EXPECT_EQ(r.o.x, -5.0);
    EXPECT_EQ(r.d.x, 0.5);  // not renormalised
    const RayInterval iv = intersectGrid(r, g.dims);
    EXPECT_EQ(iv.tEntry, 10.0);  // world distance from (-9,..) to the face at x = 1
    EXPECT_EQ(iv.tExit, 18.0);
    const GridRay rz = toGridRay({{2, 2, 10}, {0, 0, -1}}, g);
    const RayInterval ivz = intersectGrid(rz, g.dims);
    EXPECT_EQ(ivz.tEntry, 7.0);
    EXPECT_EQ(ivz.tExit, 9.0);
}

TEST(RenderRaySetup, LatticeAndVoxels) {
    EXPECT_EQ(latticeCount({0, 2}, 0.5), 4);   // 0, 0.5, 1, 1.5: 2 is not < 2
    EXPECT_EQ(latticeCount({0, 2.1}, 0.5), 5);
    EXPECT_EQ(latticeCount({0.3, 0.4}, 10), 1);
    EXPECT_EQ(latticeCount({1, 1}, 0.5), 0);
    // Every counted sample is before the exit and the next one is not, for awkward steps.
    for (double dt : {0.1, 0.3, 1.0 / 3, 0.7, 1e-3}) {
        const RayInterval iv{0.1, 6.1};
        const int64_t k = latticeCount(iv, dt);
        EXPECT_LT(latticeT(iv, dt, k - 1), iv.tExit);
        EXPECT_GE(latticeT(iv, dt, k), iv.tExit);
    }
    // Voxel of a sample: floor, then clamped into [0, N) (the crop box of an unclipped render).
    const RayClip dims{{0, 0, 0}, {4, 4, 4}, {}};
    const GridRay r{{0, 3.5, 2}, {1, 0, 0}};
    EXPECT_EQ(sampleVoxel(r, 0, dims), (Vec3i{0, 3, 2}));
    EXPECT_EQ(sampleVoxel(r, 2, dims), (Vec3i{2, 3, 2}));  // exactly on a face: the voxel beyond it
    EXPECT_EQ(sampleVoxel(r, 4, dims), (Vec3i{3, 3, 2}));  // on the far face: clamped
    EXPECT_EQ(sampleVoxel(r, -1e-17, dims), (Vec3i{0, 3, 2}));
}

TEST(RenderRaySetupLeapCount, ProximityClouds) {
    const GridRay r{{0.5, 0.5, 0.5}, normalize(Vec3d{1, 0.5, 0})};
    const double speed = r.d.x;
    EXPECT_EQ(pcLeapSamples(0, 0.5, r), 1.0);  // r = 0: constant stepping
    // (n - 1) dt max|d| <= r: the last sample moved at most r voxels on every axis.
    EXPECT_EQ(pcLeapSamples(2, 0.5, r), 1 + std::floor(2 / (0.5 * speed)));
    EXPECT_EQ(pcLeapSamples(2, 0.5, {{0, 0, 0}, {1, 0, 0}}), 5.0);
    EXPECT_EQ(pcLeapSamples(255, 1e-6, {{0, 0, 0}, {0, 0, -1}}), 1 + std::floor(255 / 1e-6));
}

TEST(RenderRaySetupLeapCount, BoxExitWithZeroComponents) {
    // Along +x only: y and z never limit (+inf, not 0/0).
    const GridRay r{{2.5, 3.5, 4.5}, {1, 0, 0}};
    EXPECT_EQ(boxExitT(r, {2, 3, 4}, 0, {3, 3, 3}), 2.5);
    EXPECT_EQ(boxExitT(r, {2, 3, 4}, 0, {3, 1, 1}), 2.5);
    // Along -x (octant 1): the far face is v - ext + 1.
    const GridRay l{{2.5, 3.5, 4.5}, {-1, 0, 0}};
    EXPECT_EQ(boxExitT(l, {2, 3, 4}, 1, {2, 2, 2}), 1.5);
    // Along -0.0 on y: counts as positive, still never limits.
    const GridRay m{{2.5, 3.5, 4.5}, {-1, -0.0, 0}};
    EXPECT_EQ(boxExitT(m, {2, 3, 4}, rayOctant(m), {2, 1, 1}), 1.5);
    // A diagonal: the nearest far face wins; anisotropic d_g (not unit) keeps t in world units.
    const GridRay d{{0.25, 0.5, 0.5}, {0.5, 0.25, -0.5}};
    EXPECT_EQ(boxExitT(d, {0, 0, 0}, rayOctant(d), {4, 2, 3}), std::min({(4 - 0.25) / 0.5, 1.5 / 0.25, 2.5 / 0.5}));
    // No axis moves at all can only come from a broken ray, but must not be NaN.
    EXPECT_EQ(boxExitT({{1, 1, 1}, {0, 0, 0}}, {1, 1, 1}, 0, {1, 1, 1}), kInf);
}

TEST(RenderRaySetupLeapCount, SpansEndStrictlyBeforeTheBoxExit) {
    // Exit at t = 2.5 with dt = 0.5: samples 0 .. 2.0 (5), the sample at 2.5 lies on the face, in the next voxel.
    EXPECT_EQ(boxLeapSamples(2.5, 0, 0.5), 5.0);
    EXPECT_EQ(boxLeapSamples(2.6, 0, 0.5), 6.0);
    EXPECT_EQ(boxLeapSamples(0.1, 0, 0.5), 1.0);
    EXPECT_EQ(boxLeapSamples(-1e-12, 0, 0.5), 1.0);  // rounding put the sample past the exit: still progress
    EXPECT_EQ(boxLeapSamples(kInf, 0, 0.5), kInf);   // leapCount bounds it by the volume exit

    // The robust count: along x from 0.5 with dt 0.5, samples at x = 0.5, 1, 1.5, 2, ...
    const Vec3i dims{8, 8, 8};
    const GridRay r{{0.5, 0.5, 0.5}, {1, 0, 0}};
    const RayInterval iv = intersectGrid(r, dims);
    const int64_t kCount = latticeCount(iv, 0.5);
    EXPECT_EQ(kCount, 15);  // x = 0.5 .. 7.5
    const VoxelBox twoVoxels = octantBox({0, 0, 0}, 0, {2, 2, 2});
    // Box of x in [0, 2): the exit formula says 3 samples; a greedy request is cut back to them too.
    EXPECT_EQ(leapCount(r, iv, 0.5, 0, kCount, boxLeapSamples(boxExitT(r, {0, 0, 0}, 0, {2, 2, 2}), 0, 0.5),
                        twoVoxels), 3);
    EXPECT_EQ(leapCount(r, iv, 0.5, 0, kCount, 1e9, twoVoxels), 3);
    // Never past the volume exit, even when the box is larger than what is left.
    EXPECT_EQ(leapCount(r, iv, 0.5, 10, kCount, 1e9, VoxelBox{{-100, -100, -100}, {100, 100, 100}}), 5);
    EXPECT_EQ(leapCount(r, iv, 0.5, 14, kCount, kInf, VoxelBox{{-100, -100, -100}, {100, 100, 100}}), 1);
    // Always at least one sample, even when the far face cuts the span right after it (x = 1.5 in voxel 1, 2 next).
    EXPECT_EQ(leapCount(r, iv, 0.5, 2, kCount, 4, VoxelBox{{1, 0, 0}, {1, 0, 0}}), 1);
    // Descending: the far face is the box's low face, and a sample exactly on it lies in the box (floor(5) = 5).
    const GridRay l{{7.5, 0.5, 0.5}, {-1, 0, 0}};
    const RayInterval ivl = intersectGrid(l, dims);
    const VoxelBox threeVoxels = octantBox({7, 0, 0}, rayOctant(l), {3, 1, 1});  // x in 5 .. 7
    EXPECT_EQ(leapCount(l, ivl, 0.5, 0, latticeCount(ivl, 0.5), 1e9, threeVoxels), 6);  // x = 7.5 .. 5
    // Millions of samples in one leap.
    const double dt = 1e-6;
    const int64_t many = latticeCount(iv, dt);
    EXPECT_EQ(leapCount(r, iv, dt, 0, many, kInf, VoxelBox{{0, 0, 0}, {7, 7, 7}}), many);
    EXPECT_GT(many, 7000000);
}

TEST(RenderRaySetupLeapCount, OctantBoxAndBall) {
    const VoxelBox b = octantBox({5, 5, 5}, 0b101, {3, 2, 1});
    EXPECT_EQ(b.lo, (Vec3i{3, 5, 5}));
    EXPECT_EQ(b.hi, (Vec3i{5, 6, 5}));
    const VoxelBox c = chebyshevBall({5, 5, 5}, 2);
    EXPECT_EQ(c.lo, (Vec3i{3, 3, 3}));
    EXPECT_EQ(c.hi, (Vec3i{7, 7, 7}));
}

}  // namespace
}  // namespace vr
