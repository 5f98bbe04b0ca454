// Stereo pairs on the Vulkan casters (docs/ALGORITHMS.md section 12): the right eye reprojected
// from the left and cast again where the reprojection cannot vouch for a pixel, against both eyes cast in full. A
// structure the left eye cannot see must be re-cast, not smeared; every pixel re-cast whole is the full render's, and
// one re-cast from the band its reprojection fails in gathers only the samples from there on; every caster and blend,
// and a volume split into bricks, give the pair they give without reuse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/blend_cases.h"
#include "support/views.h"
#include "support/vulkan.h"
#include "volrender/vulkan/ray_pieces.h"

namespace vr {
namespace {

constexpr Vec3d kWallColour{1, 0, 0}, kHiddenColour{0, 1, 0};

// An opaque red wall in front of the left half of the volume and, behind it, a green block near its edge: the left
// eye (to the left) sees the wall where the block lies, the right eye sees past the wall's edge onto the block.
const GridGeometry kSceneGrid{{32, 16, 32}, {1, 1, 1}, {0, 0, 0}};

test::VoxelClass occludedBlockVoxel(const Vec3i& v) {
    if (v.z >= 24 && v.z < 28 && v.x < 16) return test::VoxelClass{1.0, kWallColour};
    if (v.z >= 2 && v.z < 8 && v.x >= 10 && v.x < 16 && v.y >= 4 && v.y < 12)
        return test::VoxelClass{1.0, kHiddenColour};
    return test::VoxelClass{0.0, {0, 0, 0}};
}

const PreparedVolume& occludedBlock() {
    static const PreparedVolume p = test::syntheticPrepared(kSceneGrid, 1.0, occludedBlockVoxel);
    return p;
}

constexpr double kSeparation = 24;

// The pair about a view of the volume along -z.
StereoPair frontPair(const PreparedVolume& p, int width, int height, double separation = kSeparation) {
    const Camera centre = Camera::fit(p.grid(), test::orbitView(0, 0, width, height, Projection::Perspective));
    return stereoPair(centre, p.grid(), separation, std::nullopt);
}

StereoPair occludedPair(int width, int height) { return frontPair(occludedBlock(), width, height); }

bool showsHidden(const Image& image, int x, int y) {
    const float* c = image.pixel(x, y);
    return c[1] > 0.5f && c[0] < 0.5f;
}

int hiddenPixels(const Image& image) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) n += showsHidden(image, x, y);
    return n;
}

// The reuse's pair against the full one: the same left eye; each right pixel re-cast whole the full render's, each
// re-cast from a depth on no more of its samples; the reused ones, and those re-cast in part, within `reusedMean` of
// it on average. Returns the share of the right eye re-cast.
double expectPairsAgree(const StereoRender& reused, const StereoRender& full, double reusedMean,
                        const std::string& what) {
    EXPECT_LE(maxAbsDifference(reused.left.image, full.left.image), 1e-6) << what;
    const Image& a = reused.right.image;
    const Image& b = full.right.image;
    double reusedError = 0;
    std::size_t reusedCount = 0, recast = 0, inPart = 0;
    for (std::size_t i = 0; i < reused.recast.size(); ++i) {
        double d = 0;
        for (int c = 0; c < 4; ++c) d = std::max(d, double(std::abs(a.rgba[4 * i + c] - b.rgba[4 * i + c])));
        if (reused.recast[i]) {
            ++recast;
            if (reused.recastFrom[i] == 0) {
                EXPECT_LE(d, 1e-6) << what << ": re-cast pixel " << i;
                EXPECT_EQ(reused.right.samples[i], full.right.samples[i]) << what << ": re-cast pixel " << i;
                continue;
            }
            EXPECT_LE(reused.right.samples[i], full.right.samples[i]) << what << ": pixel re-cast in part " << i;
            ++inPart;
        } else {
            EXPECT_EQ(reused.right.iterations[i], 0u) << what;
        }
        reusedError += d;
        ++reusedCount;
    }
    if (reusedCount > 0) {
        EXPECT_LE(reusedError / double(reusedCount), reusedMean) << what;
    }
    EXPECT_DOUBLE_EQ(reused.recastFraction, double(recast) / double(reused.recast.size())) << what;
    EXPECT_DOUBLE_EQ(reused.recastInPartFraction, double(inPart) / double(reused.recast.size())) << what;
    return reused.recastFraction;
}

// A pair cast in full and with reuse.
struct PairRenders {
    StereoRender full, reused;
};
PairRenders fullAndReused(VulkanRenderer& renderer, const GpuVolume& volume, const StereoPair& pair, Caster caster) {
    const RenderSettings s = test::renderSettings(caster, false, false);
    return {renderer.renderStereo(volume, pair, s, false), renderer.renderStereo(volume, pair, s, true)};
}

TEST(VulkanStereo, StructureOnlyTheRightEyeSeesIsRecast) {
    const StereoPair pair = occludedPair(64, 48);
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(occludedBlock(), {{Caster::Primitive, Caster::EACD}, kAllOctants});
    for (Caster caster : {Caster::Primitive, Caster::EACD}) {
        const auto [full, reused] = fullAndReused(renderer, volume, pair, caster);
        // The scene does what it is for: the block is hidden from the left eye, in sight of the right.
        ASSERT_EQ(hiddenPixels(full.left.image), 0);
        ASSERT_GE(hiddenPixels(full.right.image), 6);
        const Image& right = full.right.image;
        for (int y = 0; y < right.height; ++y)
            for (int x = 0; x < right.width; ++x)
                if (showsHidden(right, x, y)) {
                    EXPECT_TRUE(reused.recast[std::size_t(y) * right.width + x]) << "(" << x << ", " << y << ")";
                    EXPECT_TRUE(showsHidden(reused.right.image, x, y)) << "(" << x << ", " << y << ")";
                }
        const double share = expectPairsAgree(reused, full, 0.01, std::string(casterName(caster)));
        EXPECT_GT(share, 0);
        EXPECT_LT(share, 0.5);  // the wall's and the air's pixels are reused
        EXPECT_GE(reused.right.deviceMilliseconds, reused.reprojectMilliseconds);
    }
    test::expectNoValidationErrors();
}

// The occluded block's scene seen through a thin translucent haze in front of everything: the reprojection vouches
// for the haze, so a pixel that sees the block is re-cast from where the block's band starts, behind the haze's
// reprojection, and takes fewer samples than its whole ray.
const PreparedVolume& occludedBlockBehindHaze() {
    static const PreparedVolume p = test::syntheticPrepared(kSceneGrid, 1.0, [](const Vec3i& v) {
        return v.z >= 29 ? test::VoxelClass{0.1, {0.2, 0.2, 1}} : occludedBlockVoxel(v);
    });
    return p;
}

TEST(VulkanStereo, RecastStartsWhereTheReprojectionFails) {
    const PreparedVolume& p = occludedBlockBehindHaze();
    const StereoPair pair = frontPair(p, 64, 48);
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(p, {{Caster::Primitive, Caster::EACD}, kAllOctants});
    for (Caster caster : {Caster::Primitive, Caster::EACD}) {
        const auto [full, reused] = fullAndReused(renderer, volume, pair, caster);
        const Image& right = full.right.image;
        int hidden = 0, inPart = 0;
        for (int y = 0; y < right.height; ++y)
            for (int x = 0; x < right.width; ++x) {
                if (!showsHidden(right, x, y)) continue;
                const std::size_t i = std::size_t(y) * right.width + x;
                ++hidden;
                EXPECT_TRUE(reused.recast[i]) << "(" << x << ", " << y << ")";
                EXPECT_TRUE(showsHidden(reused.right.image, x, y)) << "(" << x << ", " << y << ")";
                if (reused.recastFrom[i] > 0 && reused.right.samples[i] < full.right.samples[i]) ++inPart;
            }
        ASSERT_GE(hidden, 6) << casterName(caster);
        EXPECT_GE(inPart, hidden / 2) << casterName(caster);
        expectPairsAgree(reused, full, 0.01, std::string(casterName(caster)));
    }
    test::expectNoValidationErrors();
}

// A thick translucent slab over the whole volume, in two halves of two colours along x: each ray gathers
// its colour over a depth whose disparities span several bands.
const PreparedVolume& twoColourSlab() {
    static const PreparedVolume p = test::syntheticPrepared(kSceneGrid, 1.0, [](const Vec3i& v) {
        if (v.z < 4 || v.z >= 28) return test::VoxelClass{0.0, {0, 0, 0}};
        return test::VoxelClass{0.04, v.x < 16 ? Vec3d{1, 0.6, 0.2} : Vec3d{0.2, 0.6, 1}};
    });
    return p;
}

StereoPair slabPair(int width, int height, double separation = kSeparation) {
    return frontPair(twoColourSlab(), width, height, separation);
}

// The disparities of the slab's near and far faces along the view direction.
double slabSpread(const StereoPair& pair) {
    const Vec3d middle = (pair.left.eye + pair.right.eye) * 0.5;
    double lo = INFINITY, hi = -INFINITY;
    for (double z : {4.0, 28.0}) {
        const double d = disparityAt(pair, dot(Vec3d{16, 8, z} - middle, pair.left.forward));
        lo = std::min(lo, d), hi = std::max(hi, d);
    }
    return hi - lo;
}

// A ray through the slab gathers over more disparity than one depth stands for, yet its segment of each band lands
// where it belongs: the right eye is reused, not re-cast, save the slab's edges and the image's.
TEST(VulkanStereo, TranslucentSlabIsReused) {
    const StereoPair pair = slabPair(64, 48);
    ASSERT_GT(slabSpread(pair), 2 * kMaxSpreadPixels);  // the scene does what it is for: wide rays
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(twoColourSlab(), {{Caster::Primitive, Caster::EACD}, kAllOctants});
    for (Caster caster : {Caster::Primitive, Caster::EACD}) {
        const auto [full, reused] = fullAndReused(renderer, volume, pair, caster);
        int slab = 0, slabReused = 0;
        for (std::size_t i = 0; i < reused.recast.size(); ++i)
            if (full.right.image.rgba[4 * i + 3] > 0.3f) ++slab, slabReused += !reused.recast[i];
        ASSERT_GT(slab, int(reused.recast.size() / 8));
        EXPECT_GT(slabReused, slab * 3 / 4) << casterName(caster);
        expectPairsAgree(reused, full, 0.01, std::string(casterName(caster)));
    }
    test::expectNoValidationErrors();
}

// A tall image's bands take as wide an angle of disparity as a 512-pixel image's (maxSpreadPixels: 7.5 pixels at
// 1280, ten candidates a band, read from three mask texels): the slab is still reused, and agrees with its full
// render.
TEST(VulkanStereo, TallImagesBandsSpanTheSameAngle) {
    const StereoPair pair = slabPair(256, 1280, 4 * kSeparation);  // the eyes farther apart: the view is narrow
    ASSERT_EQ(maxSpreadPixels(pair.left.height), 2.5 * kMaxSpreadPixels);
    ASSERT_GT(slabSpread(pair), 2 * maxSpreadPixels(pair.left.height));  // rays over several bands
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(twoColourSlab(), {{Caster::EACD}, kAllOctants});
    const auto [full, reused] = fullAndReused(renderer, volume, pair, Caster::EACD);
    int slab = 0, slabReused = 0;
    for (std::size_t i = 0; i < reused.recast.size(); ++i)
        if (full.right.image.rgba[4 * i + 3] > 0.3f) ++slab, slabReused += !reused.recast[i];
    ASSERT_GT(slab, int(reused.recast.size() / 32));  // a narrow view: the slab fills a twentieth of it
    EXPECT_GT(slabReused, slab * 3 / 4);
    expectPairsAgree(reused, full, 0.01, "256 x 1280");
    test::expectNoValidationErrors();
}

// A leap over a homogeneous span is split at the band ends it crosses, in closed form: the bands it records, and so
// the reused right eye, are those of the same span stepped sample by sample.
TEST(VulkanStereo, LeapSplitAcrossBandsEqualsSteppedSamples) {
    const StereoPair pair = slabPair(64, 48);
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(twoColourSlab(), {{Caster::Primitive, Caster::EACD}, kAllOctants});
    const StereoRender stepped =
        renderer.renderStereo(volume, pair, test::renderSettings(Caster::Primitive, false), true);
    const StereoRender leapt = renderer.renderStereo(volume, pair, test::renderSettings(Caster::EACD, false), true);
    // The leaps are real: EACD takes far fewer iterations than samples.
    std::uint64_t samples = 0, iterations = 0;
    for (std::size_t i = 0; i < leapt.left.samples.size(); ++i)
        samples += leapt.left.samples[i], iterations += leapt.left.iterations[i];
    ASSERT_LT(4 * iterations, samples);
    EXPECT_EQ(leapt.recast, stepped.recast);
    EXPECT_LE(maxAbsDifference(leapt.right.image, stepped.right.image), 1e-4);
    test::expectNoValidationErrors();
}

// A faint green haze (below kFaintAlpha in all, so faint in every band) in front of an opaque red wall, with
// empty bands in front of it: the reprojection skips only bands whose candidate segments hold nothing at all, so
// the haze's faint pieces are composited over the wall, as the full render shows them.
const PreparedVolume& hazeOverWall() {
    static const PreparedVolume p = test::syntheticPrepared(kSceneGrid, 1.0, [](const Vec3i& v) {
        if (v.z >= 2 && v.z < 6) return test::VoxelClass{1.0, kWallColour};
        if (v.z >= 8 && v.z < 30) return test::VoxelClass{0.0005, {0, 1, 0}};
        return test::VoxelClass{0.0, {0, 0, 0}};
    });
    return p;
}

TEST(VulkanStereo, FaintHazeIsCompositedWhereEmptyBandsAreSkipped) {
    const PreparedVolume& p = hazeOverWall();
    const StereoPair pair = frontPair(p, 64, 48);
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(p, {{Caster::Primitive, Caster::EACD}, kAllOctants});
    for (Caster caster : {Caster::Primitive, Caster::EACD}) {
        const auto [full, reused] = fullAndReused(renderer, volume, pair, caster);
        int wall = 0;
        for (std::size_t i = 0; i < reused.recast.size(); ++i) {
            const float* f = &full.right.image.rgba[4 * i];
            if (reused.recast[i] || f[3] < 0.99f) continue;
            ++wall;
            // The scene does what it is for: the haze shows, and is faint. Skipping its bands would lose all of it.
            ASSERT_GT(f[1], 0.005f) << i;
            ASSERT_LT(f[1], float(kFaintAlpha)) << i;
            EXPECT_NEAR(reused.right.image.rgba[4 * i + 1], f[1], 0.25f * f[1]) << casterName(caster) << ": " << i;
        }
        EXPECT_GT(wall, int(reused.recast.size() / 16)) << casterName(caster);
        expectPairsAgree(reused, full, 0.01, std::string(casterName(caster)));
    }
    test::expectNoValidationErrors();
}

// A re-cast ray cast in pieces, each a stretch of its samples gathered from a transparent start, composites to the
// whole ray's pixel: through haze over a wall and through a translucent slab, stepped and leapt.
TEST(VulkanStereo, RecastRaysInPiecesAreTheWholeRays) {
    VulkanRenderer whole(test::vulkanContext(), 16), pieced(test::vulkanContext(), 16);
    whole.setRecastPieces(1);
    for (const PreparedVolume* p : {&hazeOverWall(), &twoColourSlab()}) {
        const StereoPair pair = frontPair(*p, 64, 48);
        const GpuVolume a = whole.upload(*p, {{Caster::Primitive, Caster::EACD}, kAllOctants});
        const GpuVolume b = pieced.upload(*p, {{Caster::Primitive, Caster::EACD}, kAllOctants});
        for (Caster caster : {Caster::Primitive, Caster::EACD}) {
            const RenderSettings s = test::renderSettings(caster, false, false);
            const StereoRender one = whole.renderStereo(a, pair, s, true);
            EXPECT_EQ(one.recastPieces, 1);
            for (int pieces : {2, 3, device::kMostPieces}) {
                const std::string what = std::string(casterName(caster)) + ", " + std::to_string(pieces) + " pieces";
                pieced.setRecastPieces(pieces);
                const StereoRender split = pieced.renderStereo(b, pair, s, true);
                EXPECT_EQ(split.recastPieces, pieces) << what;
                ASSERT_EQ(split.recast, one.recast) << what;
                EXPECT_LE(maxAbsDifference(split.right.image, one.right.image), 1e-5) << what;
                // The pieces are real: each starts an iteration of its own, where a leap would have crossed it.
                std::uint64_t wholeIterations = 0, pieceIterations = 0, recast = 0;
                for (std::size_t i = 0; i < one.recast.size(); ++i) {
                    if (!one.recast[i]) continue;
                    ++recast;
                    wholeIterations += one.right.iterations[i];
                    pieceIterations += split.right.iterations[i];
                    EXPECT_GE(split.right.samples[i], one.right.samples[i]) << what << ": pixel " << i;
                }
                ASSERT_GT(recast, 0u) << what;
                if (caster == Caster::EACD) {
                    EXPECT_GT(pieceIterations, wholeIterations) << what;
                } else {
                    EXPECT_GE(pieceIterations, wholeIterations) << what;
                }
            }
        }
    }
    test::expectNoValidationErrors();
}

// Eyes inside the volume's bounding sphere would need bands from any disparity in front of them: composite casts
// the right eye in full.
TEST(VulkanStereo, EyesInsideTheVolumeCastTheRightEyeInFull) {
    const PreparedVolume& p = twoColourSlab();
    Camera centre = Camera::fit(p.grid(), test::orbitView(0, 0, 32, 24, Projection::Perspective));
    centre.eye = p.grid().centre() - centre.forward * 2.0;
    ASSERT_LE(depthRange(stereoPair(centre, p.grid(), 1, 8), p.grid()).nearest, 0);
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(p, {{Caster::Primitive}, kAllOctants});
    const auto [full, reused] = fullAndReused(renderer, volume, stereoPair(centre, p.grid(), 1, 8), Caster::Primitive);
    EXPECT_EQ(reused.recastFraction, 1.0);
    EXPECT_LE(maxAbsDifference(reused.right.image, full.right.image), 1e-6);
    test::expectNoValidationErrors();
}

TEST(VulkanStereo, EveryCasterGivesThePairWithoutReuse) {
    const StereoPair pair = occludedPair(40, 32);
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume =
        renderer.upload(occludedBlock(), {{std::begin(test::kCasters), std::end(test::kCasters)}, kAllOctants});
    for (Caster caster : test::kCasters) {
        const RenderSettings s = test::renderSettings(caster, false, false);
        expectPairsAgree(renderer.renderStereo(volume, pair, s, true), renderer.renderStereo(volume, pair, s, false),
                         0.01, std::string(casterName(caster)));
    }
    test::expectNoValidationErrors();
}

// MIP, MinIP and average depend on every sample of a ray: only rays that miss the volume are reused. The
// iso-surface carries its hit.
TEST(VulkanStereo, EveryBlendGivesThePairWithoutReuse) {
    const test::BlendVolume& v = test::blendVolumes().front();
    VulkanRenderer& renderer = test::vulkanRenderer(16);
    const GpuVolume volume = renderer.upload(v.prepared, {{Caster::Primitive, Caster::Blocks}, kAllOctants});
    const Camera centre = Camera::fit(v.prepared.grid(), test::orbitView(30, 20, 40, 32, Projection::Perspective));
    const double separation = 0.05 * length(v.prepared.grid().extent());
    const StereoPair pair = stereoPair(centre, v.prepared.grid(), separation, std::nullopt);
    for (Blend blend : {Blend::Composite, Blend::MIP, Blend::MinIP, Blend::Average, Blend::Iso})
        for (Caster caster : {Caster::Primitive, Caster::Blocks}) {
            if (blend == Blend::Composite && caster == Caster::Blocks) continue;
            const RenderSettings s = test::blendSettings(blend, caster, true, v.isoValue);
            const std::string what = std::string(blendName(blend)) + " " + std::string(casterName(caster));
            const double share = expectPairsAgree(renderer.renderStereo(volume, pair, s, true),
                                                  renderer.renderStereo(volume, pair, s, false), 0.02, what);
            EXPECT_GT(share, 0);
        }
    test::expectNoValidationErrors();
}

// volrender makes a pair's pipelines while the volume is being prepared: the ones the pair then takes, no other.
// (PC: the test volume's EACD is in the exact code, not the default one that volrender prepares for.)
TEST(VulkanStereo, PreparedPipelinesAreThePairs) {
    const StereoPair pair = occludedPair(40, 32);
    VulkanRenderer renderer(test::vulkanContext(), 16);
    // Whole re-cast rays: on a discrete GPU the pieces follow the list's size, which the prepare can only guess.
    renderer.setRecastPieces(1);
    const GpuVolume volume = renderer.upload(occludedBlock(), {{Caster::PC}, kAllOctants});
    const RenderSettings s = test::renderSettings(Caster::PC, false, false);
    EXPECT_EQ(renderer.pipelineCount(), 0u);
    renderer.prepareStereoPipelines(s, volume.scalarType());
    EXPECT_EQ(renderer.pipelineCount(), 3u);  // the left eye's, the re-casts', the reprojection's
    const StereoRender pairRender = renderer.renderStereo(volume, pair, s, true);
    ASSERT_GT(pairRender.recastFraction, 0);  // the re-casts' pipeline was taken
    EXPECT_EQ(renderer.pipelineCount(), 3u);

    const test::BlendVolume& v = test::blendVolumes().front();
    const GpuVolume blocks = renderer.upload(v.prepared, {{Caster::Blocks}, kAllOctants});
    const Camera centre = Camera::fit(v.prepared.grid(), test::orbitView(30, 20, 40, 32, Projection::Perspective));
    const StereoPair mipPair =
        stereoPair(centre, v.prepared.grid(), 0.05 * length(v.prepared.grid().extent()), std::nullopt);
    const RenderSettings mip = test::blendSettings(Blend::MIP, Caster::Blocks, true, v.isoValue);
    renderer.prepareStereoPipelines(mip, blocks.scalarType());
    EXPECT_EQ(renderer.pipelineCount(), 6u);  // MIP's left eye is its frame's; the re-casts'; the reprojection's
    ASSERT_GT(renderer.renderStereo(blocks, mipPair, mip, true).recastFraction, 0);
    EXPECT_EQ(renderer.pipelineCount(), 6u);
    test::expectNoValidationErrors();
}

// Bricks carry each ray's depth interval from dispatch to dispatch, and the re-cast list runs through every brick.
TEST(VulkanStereo, BrickedVolumeGivesTheWholeVolumesPair) {
    VulkanRenderer bricked(test::vulkanContext(), 16, ImageLimits{.maxDimension = 24, .minBricks = {2, 2, 2}});
    VulkanRenderer& whole = test::vulkanRenderer(16);
    const StereoPair pair = occludedPair(48, 32);
    for (Caster caster : {Caster::Primitive, Caster::PC}) {
        const RenderSettings s = test::renderSettings(caster, false, false);
        const GpuVolume split = bricked.upload(occludedBlock(), {{caster}, kAllOctants});
        ASSERT_GT(split.bricks().bricks().size(), 1u);
        const StereoRender a = bricked.renderStereo(split, pair, s, true);
        const GpuVolume one = whole.upload(occludedBlock(), {{caster}, kAllOctants});
        const StereoRender b = whole.renderStereo(one, pair, s, true);
        EXPECT_EQ(a.recast, b.recast) << casterName(caster);
        EXPECT_LE(maxAbsDifference(a.right.image, b.right.image), 1e-5) << casterName(caster);
        expectPairsAgree(a, bricked.renderStereo(split, pair, s, false), 0.01, "bricked");
    }
    test::expectNoValidationErrors();
}

}  // namespace
}  // namespace vr
