// Clipping (docs/ALGORITHMS.md section 1): the ray's interval is cut by the crop box and the planes before casting,
// so that every sample lies on the kept side, the leaping casters still render the primitive caster's image, and
// what is cut away shows the background. Bad planes and crops are refused with the flag named.
#include <gtest/gtest.h>

#include <numeric>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "render/cpu_renderer.h"
#include "render/ray_setup.h"
#include "support/blend_cases.h"
#include "support/load_dataset.h"
#include "support/prepare.h"
#include "support/views.h"
#include "support/volumes.h"

namespace vr {
namespace {

// The shared rule (shaders/clip_planes.h) on its four cases: an entry, an exit, a parallel ray inside, outside.
TEST(RenderClipping, PlaneCutsTheIntervalFromTheKeptSide) {
    const GridRay along{{-1, 1.5, 1.5}, {1, 0, 0}};  // x = t - 1
    const RayClip keepFar{{0, 0, 0}, {10, 4, 4}, {{{1, 0, 0}, 6}}};  // x >= 6
    RayInterval iv = clipInterval(along, keepFar);
    EXPECT_DOUBLE_EQ(iv.tEntry, 7);
    EXPECT_DOUBLE_EQ(iv.tExit, 11);
    const RayClip keepNear{{0, 0, 0}, {10, 4, 4}, {{{-2, 0, 0}, -12}}};  // x <= 6
    iv = clipInterval(along, keepNear);
    EXPECT_DOUBLE_EQ(iv.tEntry, 1);
    EXPECT_DOUBLE_EQ(iv.tExit, 7);
    const RayClip inside{{0, 0, 0}, {10, 4, 4}, {{{0, 1, 0}, 1}}};  // y >= 1: the ray runs at y = 1.5
    iv = clipInterval(along, inside);
    EXPECT_DOUBLE_EQ(iv.tEntry, 1);
    EXPECT_DOUBLE_EQ(iv.tExit, 11);
    const RayClip outside{{0, 0, 0}, {10, 4, 4}, {{{0, 1, 0}, 2}}};  // y >= 2
    EXPECT_TRUE(clipInterval(along, outside).empty());
    const RayClip both{{0, 0, 0}, {10, 4, 4}, {keepFar.planes[0], keepNear.planes[0]}};  // x = 6 only: empty
    EXPECT_TRUE(clipInterval(along, both).empty());
    // The crop box's faces: voxels 2..4 on x are [2, 5].
    RenderSettings s;
    s.crop = CropBox{{2, 0, 0}, {4, 3, 3}};
    const GridGeometry grid{{10, 4, 4}, {1, 1, 1}, {0, 0, 0}};
    iv = clipInterval(along, RayClip::of(grid, s));
    EXPECT_DOUBLE_EQ(iv.tEntry, 3);
    EXPECT_DOUBLE_EQ(iv.tExit, 6);
}

// World planes on an anisotropic, displaced grid: every lattice sample of every pixel's ray lies on the kept side
// of each plane and in the crop box, and the samples at the clipped ends are the ones the planes cut at.
TEST(RenderClipping, EverySampleLiesOnTheKeptSide) {
    const GridGeometry grid{{30, 24, 18}, {0.7, 1.1, 2.3}, {-5, 12, 3}};
    const double dt = 0.5 * grid.smallestSpacing();
    for (const test::Clipping& c : test::clippings(grid))
        for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
            RenderSettings s;
            c.applyTo(s);
            const RayClip clip = RayClip::of(grid, s);
            const Camera cam = Camera::fit(grid, test::orbitView(35, 25, 24, 20, p));
            long long samples = 0, kept = 0;
            for (int py = 0; py < cam.height; ++py)
                for (int px = 0; px < cam.width; ++px) {
                    const Ray ray = cam.ray(px + 0.5, py + 0.5);
                    const GridRay g = toGridRay(ray, grid);
                    const RayInterval iv = clipInterval(g, clip);
                    const int64_t n = latticeCount(iv, dt);
                    samples += latticeCount(intersectGrid(g, grid.dims), dt);
                    kept += n;
                    for (int64_t k = 0; k < n; ++k) {
                        const double t = latticeT(iv, dt, k);
                        const Vec3d world = ray.origin + ray.direction * t;
                        for (const ClipPlane& plane : c.planes)
                            ASSERT_GE(dot(plane.normal, world), plane.offset - 1e-9) << c.name;
                        const Vec3d at = g.at(t);
                        const Vec3i voxel = sampleVoxel(g, t, clip);
                        for (int a = 0; a < 3; ++a) {
                            ASSERT_GE(at[a], clip.lo[a] - 1e-9) << c.name;
                            ASSERT_LT(at[a], clip.hi[a] + 1e-9) << c.name;
                            ASSERT_GE(voxel[a], clip.lo[a]) << c.name;
                            ASSERT_LT(voxel[a], clip.hi[a]) << c.name;
                        }
                    }
                }
            std::printf("%s, %s: %lld of %lld samples kept\n", c.name.c_str(),
                        p == Projection::Perspective ? "perspective" : "ortho", kept, samples);
            EXPECT_GT(kept, 0) << c.name;
            EXPECT_LT(kept, samples) << c.name;
        }
}

double meanOf(const std::vector<uint32_t>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

// docs/ALGORITHMS.md section 5 under clipping: at thresholds 0 the leaping casters render the primitive caster's
// image, with no more fetches, for every clipping; and the clipping changes the image.
TEST(RenderClipping, LeapingCastersEqualPrimitive) {
    const test::DatasetEntry head = test::rawDataset("vtk_headsq_ct");
    const struct {
        std::string name;
        Volume volume;
        TransferFunction tf;
    } volumes[] = {
        {"shells", shellsPhantom({40, 36, 24}, {1, 1, 2}), test::datasetTransferFunction("cranium_ct.tf.json")},
        {"engine", enginePhantom({48, 40, 36}, {0.8, 0.8, 1.2}), test::datasetTransferFunction("mri.tf.json")},
        {head.file, test::centralBlock(test::loadDataset(head), 48), test::datasetTransferFunction(head.tf)}};
    for (const auto& v : volumes) {
        const PreparedVolume p = test::prepareVolume(v.volume, v.tf, {0, 0, true, false});
        for (const ViewParams& view : {test::orbitView(0, 0, 40, 32), test::orbitView(37, 23, 40, 32),
                                       test::orbitView(-130, -50, 40, 32, Projection::Perspective)}) {
            const Camera cam = Camera::fit(p.grid(), view);
            RenderSettings s = test::renderSettings(Caster::Primitive);
            const RenderResult whole = renderCpu(p, cam, s);
            for (const test::Clipping& c : test::clippings(p.grid())) {
                SCOPED_TRACE(v.name + ", " + c.name + ", az " + std::to_string(view.azimuthDeg));
                c.applyTo(s);
                s.caster = Caster::Primitive;
                const RenderResult primitive = renderCpu(p, cam, s);
                EXPECT_GT(maxAbsDifference(primitive.image, whole.image), 0.01);
                for (Caster caster : {Caster::PC, Caster::ACD, Caster::EACD, Caster::Hier}) {
                    s.caster = caster;
                    const RenderResult r = renderCpu(p, cam, s);
                    EXPECT_LT(maxAbsDifference(r.image, primitive.image), 1e-6) << casterName(caster);
                    EXPECT_LE(meanOf(r.iterations), meanOf(primitive.iterations)) << casterName(caster);
                }
            }
        }
    }
}

// The iso-surface under every clipping: its bisection stays between two samples of the clipped interval, so the
// blocks caster, whose leaps stop at the interval's exit, finds the primitive caster's surface, and what is cut away
// shows no surface.
TEST(RenderClipping, IsoSurfaceBlocksEqualPrimitive) {
    for (const test::BlendVolume& v : test::blendVolumes()) {
        const Camera cam = Camera::fit(v.prepared.grid(), test::orbitView(37, 23, 40, 32));
        for (bool trilinear : {false, true}) {
            RenderSettings s = test::blendSettings(Blend::Iso, Caster::Primitive, trilinear, v.isoValue);
            const RenderResult whole = renderCpu(v.prepared, cam, s);
            for (const test::Clipping& c : test::clippings(v.prepared.grid())) {
                SCOPED_TRACE(v.name + ", " + c.name + (trilinear ? ", trilinear" : ", nearest"));
                c.applyTo(s);
                s.caster = Caster::Primitive;
                const RenderResult primitive = renderCpu(v.prepared, cam, s);
                EXPECT_GT(maxAbsDifference(primitive.image, whole.image), 0.01);
                s.caster = Caster::Blocks;
                EXPECT_LT(maxAbsDifference(renderCpu(v.prepared, cam, s).image, primitive.image), 1e-7);
            }
        }
    }
}

// A crop to the lower half of x, or a plane keeping x below the middle: seen along -z, the image's right half is
// the background exactly and its left half is not.
TEST(RenderClipping, WhatIsCutAwayShowsTheBackground) {
    const PreparedVolume p =
        test::prepareVolume(constantPhantom({20, 16, 12}, 200), test::datasetTransferFunction("mri.tf.json"),
                            {0, 0, true, false});
    const Camera cam = Camera::fit(p.grid(), test::orbitView(0, 0, 40, 40));
    RenderSettings crop = test::renderSettings(Caster::EACD);
    crop.background = {0.2, 0.4, 0.6};
    RenderSettings plane = crop;
    crop.crop = CropBox{{0, 0, 0}, {9, 15, 11}};
    plane.clipPlanes = {{{-1, 0, 0}, -p.grid().centre().x}};
    for (const RenderSettings& s : {crop, plane}) {
        const RenderResult r = renderCpu(p, cam, s);
        int volume = 0, background = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const Vec3d at = cam.ray(x + 0.5, y + 0.5).origin;
                if (at.y <= 0.5 || at.y >= 15.5 || std::abs(at.x - 10) < 0.5 || at.x <= 0.5 || at.x >= 19.5)
                    continue;  // outside the volume's footprint or at the cut
                const float* px = r.image.pixel(x, y);
                const bool isBackground = px[0] == 0.2f && px[1] == 0.4f && px[2] == 0.6f;
                EXPECT_EQ(isBackground, at.x > 10) << "pixel " << x << ", " << y;
                (isBackground ? background : volume) += 1;
            }
        EXPECT_GT(volume, 100);
        EXPECT_GT(background, 100);
    }
}

TEST(RenderClipping, BadPlanesAndCropsAreRefused) {
    const PreparedVolume p = test::prepareVolume(constantPhantom({8, 8, 8}, 200),
                                                 test::datasetTransferFunction("mri.tf.json"), {0, 0, true, false});
    const Camera cam = Camera::fit(p.grid(), test::orbitView(0, 0, 8, 8));
    auto refusal = [&](const RenderSettings& s) {
        try {
            renderCpu(p, cam, s);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("rendered");
    };
    RenderSettings s = test::renderSettings(Caster::Primitive);
    for (const ClipPlane& bad : {ClipPlane{{0, 0, 0}, 1}, ClipPlane{{std::nan(""), 1, 0}, 0},
                                 ClipPlane{{0, 1, 0}, double(INFINITY)}, ClipPlane{{1e308, 1e308, 0}, 0}}) {
        s.clipPlanes = {bad};
        EXPECT_NE(refusal(s).find("--clip"), std::string::npos) << refusal(s);
    }
    s.clipPlanes.assign(7, ClipPlane{{0, 0, 1}, 0});
    EXPECT_NE(refusal(s).find("at most 6"), std::string::npos) << refusal(s);
    s.clipPlanes.resize(6);
    EXPECT_EQ(refusal(s), "rendered");
    s.clipPlanes.clear();
    for (const CropBox& bad : {CropBox{{0, 0, 0}, {8, 7, 7}}, CropBox{{-1, 0, 0}, {7, 7, 7}},
                               CropBox{{0, 5, 0}, {7, 4, 7}}, CropBox{{9, 9, 9}, {12, 12, 12}}}) {
        s.crop = bad;
        EXPECT_NE(refusal(s).find("--crop"), std::string::npos) << refusal(s);
    }
    s.crop = CropBox{{7, 0, 3}, {7, 7, 3}};  // one voxel thick
    EXPECT_EQ(refusal(s), "rendered");
}

}  // namespace
}  // namespace vr
