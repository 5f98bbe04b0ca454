// The CPU reference renderer on volumes with known answers: stiff opacities, opaque volumes, huge leaps, a camera
// inside the volume, the background, counters and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/errors.h"
#include "preprocess/fields/build_fields.h"
#include "render/cpu_renderer.h"
#include "render/span.h"
#include "render/view_octants.h"
#include "support/views.h"

namespace vr {
namespace {

constexpr Caster kCasters[] = {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD};

// A transfer table of one entry per scalar 0, 1, ...: opacity per unit step and colour.
TransferTable tableOf(const std::vector<std::pair<double, std::array<float, 3>>>& entries) {
    TransferTable t;
    for (const auto& e : entries) {
        t.sigma.push_back(float(extinctionFromOpacity(e.first, 1.0)));
        t.colour.push_back(e.second);
    }
    return t;
}

// A constant volume (scalar 0: one region) with every distance field, unit spacing, origin 0; regions made with
// normals when `normals` (shaded leaping needs them).
PreparedVolume constantVolume(Vec3i dims, double opacityPerVoxel, bool normals = false) {
    PreparedVolume p;
    p.scalars.grid.dims = dims;
    p.scalars.sourceType = ScalarType::UInt8;
    p.scalars.values.assign(p.scalars.grid.voxels(), 0.f);
    p.classification.table = tableOf({{opacityPerVoxel, {0.5f, 0.75f, 1.0f}}});
    p.meta.segmentation.useNormals = normals;
    p.regions.dims = dims;
    p.regions.label.assign(p.grid().voxels(), 0);
    p.regions.count = 1;
    p.fields = buildFields(p.regions, kFieldPC | kFieldACD | kFieldEACD);
    return p;
}

ViewParams axisView(int size) {
    ViewParams v;
    v.width = v.height = size;
    return v;
}

RenderSettings unshaded(Caster c, double step = 0.5) {
    RenderSettings s;
    s.caster = c;
    s.shading = false;
    s.stepVoxels = step;
    return s;
}

TEST(RenderCpuRenderer, TinyOpacityAccumulatesAlongAnAxis) {
    // 64 voxels of opacity 1e-9: alpha = 1 - (1 - 1e-9)^64, which float stepping would round away.
    const PreparedVolume p = constantVolume({64, 64, 64}, 1e-9);
    const Camera cam = Camera::fit(p.grid(), axisView(9));
    const double want = 1 - std::pow(1 - 1e-9, 64);
    for (Caster c : kCasters) {
        const RenderResult r = renderCpu(p, cam, unshaded(c));
        const float alpha = r.image.pixel(4, 4)[3];
        EXPECT_NEAR(alpha, want, 0.01 * want) << casterName(c);
        EXPECT_NEAR(r.image.pixel(4, 4)[2], want, 0.01 * want) << casterName(c);  // blue 1.0, premultiplied
        EXPECT_EQ(r.samples[4 * 9 + 4], 128u) << casterName(c);                   // 64 voxels at step 0.5
    }
}

TEST(RenderCpuRenderer, MillionsOfSamplesInOneLeap) {
    // dt = 1e-5 voxels: 6.4 million samples per ray; leaping casters cover them in a handful of fetches.
    const PreparedVolume p = constantVolume({64, 64, 64}, 1e-6);
    const Camera cam = Camera::fit(p.grid(), axisView(1));
    const double want = 1 - std::pow(1 - 1e-6, 64);
    for (Caster c : kCasters) {
        const RenderResult r = renderCpu(p, cam, unshaded(c, 1e-5));
        EXPECT_NEAR(r.image.pixel(0, 0)[3], want, 1e-4 * want) << casterName(c);
        EXPECT_NEAR(double(r.samples[0]), 6.4e6, 1) << casterName(c);
        if (c == Caster::Primitive) {
            EXPECT_EQ(uint64_t(r.iterations[0]), r.samples[0]);
        } else if (c != Caster::PC) {
            EXPECT_LE(r.iterations[0], 3u) << casterName(c);
        }
    }
}

TEST(RenderCpuRenderer, OpaqueVolumeTerminatesAtTheFirstSample) {
    const PreparedVolume p = constantVolume({16, 16, 16}, 1.0, true);
    const Camera cam = Camera::fit(p.grid(), axisView(5));
    for (Caster c : kCasters) {
        RenderSettings s;
        s.caster = c;
        s.stepVoxels = 1.0;  // one reference step: alpha 1 - 1e-12, which is 1 in the float image
        const RenderResult r = renderCpu(p, cam, s);
        EXPECT_EQ(r.image.pixel(2, 2)[3], 1.0f) << casterName(c);
        EXPECT_EQ(r.iterations[2 * 5 + 2], 1u) << casterName(c);
        EXPECT_EQ(r.samples[2 * 5 + 2], 1u) << casterName(c);  // the span stops where primitive stepping would
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(std::isfinite(r.image.pixel(2, 2)[a]));
    }
}

TEST(RenderCpuRenderer, BackgroundAndMissingRays) {
    const PreparedVolume p = constantVolume({8, 8, 8}, 0.1);
    const Camera cam = Camera::fit(p.grid(), axisView(32));
    RenderSettings s = unshaded(Caster::EACD, 1.0);
    s.background = {0.25, 0.5, 1.0};
    const RenderResult r = renderCpu(p, cam, s);
    // The corner ray misses the cube (it lies inside the bounding sphere's square only).
    const float* corner = r.image.pixel(0, 0);
    EXPECT_EQ(corner[3], 0.f);
    EXPECT_EQ(corner[0], 0.25f);
    EXPECT_EQ(corner[2], 1.0f);
    EXPECT_EQ(r.iterations[0], 0u);
    // The centre: 8 samples of alpha 0.1 over the background.
    const double a = 1 - std::pow(0.9, 8);
    const float* c = r.image.pixel(16, 16);
    EXPECT_NEAR(c[3], a, 1e-6);
    EXPECT_NEAR(c[0], 0.5 * a + 0.25 * (1 - a), 1e-6);
    EXPECT_NEAR(c[2], 1.0 * a + 1.0 * (1 - a), 1e-6);
}

TEST(RenderCpuRenderer, CameraInsideTheVolume) {
    const PreparedVolume p = constantVolume({32, 32, 32}, 0.01);
    Camera cam = Camera::fit(p.grid(), axisView(11));
    cam.projection = Projection::Perspective;
    cam.halfHeight = std::tan(0.3);
    cam.eye = {16, 16, 10};  // 10 voxels from the z = 0 face it looks at
    const double want = 1 - std::pow(0.99, 10);
    RenderResult first;
    for (Caster c : kCasters) {
        const RenderResult r = renderCpu(p, cam, unshaded(c, 0.5));
        EXPECT_NEAR(r.image.pixel(5, 5)[3], want, 1e-6) << casterName(c);
        if (c == Caster::Primitive) {
            first = r;
        } else {
            EXPECT_LT(maxAbsDifference(first.image, r.image), 1e-6) << casterName(c);
        }
    }
}

TEST(RenderCpuRenderer, CountsAndShadedConstant) {
    const PreparedVolume p = constantVolume({20, 20, 20}, 0.001, true);
    const Camera cam = Camera::fit(p.grid(), axisView(3));
    RenderSettings s;
    s.caster = Caster::Primitive;
    s.stepVoxels = 0.25;
    const RenderResult prim = renderCpu(p, cam, s);
    EXPECT_EQ(prim.samples[4], 80u);
    EXPECT_EQ(prim.iterations[4], 80u);
    s.caster = Caster::EACD;
    const RenderResult eacd = renderCpu(p, cam, s);
    EXPECT_EQ(eacd.samples[4], 80u);
    EXPECT_LT(eacd.iterations[4], 10u);
    EXPECT_LT(maxAbsDifference(prim.image, eacd.image), 1e-7);
    EXPECT_GT(prim.wallMilliseconds, 0);
    EXPECT_EQ(prim.iterations.size(), 9u);
}

TEST(RenderCpuRenderer, ErrorsAreReported) {
    PreparedVolume p = constantVolume({16, 16, 16}, 0.01);
    const Camera cam = Camera::fit(p.grid(), axisView(4));
    // A runaway ray is reported, not hung.
    RenderSettings capped = unshaded(Caster::Primitive, 0.5);
    capped.maxIterationsPerRay = 5;
    EXPECT_THROW(renderCpu(p, cam, capped), std::runtime_error);
    // Shaded leaping over regions made without normals, a bad step, a bad ert.
    RenderSettings s;
    s.caster = Caster::EACD;
    EXPECT_THROW(renderCpu(p, cam, s), InputError);
    s.caster = Caster::Primitive;
    EXPECT_NO_THROW(renderCpu(p, cam, s));  // stepping takes each sample's own normal
    s = unshaded(Caster::Primitive, 0);
    EXPECT_THROW(renderCpu(p, cam, s), InputError);
    s = unshaded(Caster::Primitive);
    s.ert = 1.5;
    EXPECT_THROW(renderCpu(p, cam, s), InputError);
    s = unshaded(Caster::Primitive);
    s.lightDirection = Vec3d{0, 0, 0};
    EXPECT_THROW(renderCpu(p, cam, s), InputError);
    // A caster whose field is missing.
    p.fields.pc.clear();
    EXPECT_THROW(renderCpu(p, cam, unshaded(Caster::PC)), InputError);
    EXPECT_NO_THROW(renderCpu(p, cam, unshaded(Caster::ACD)));
    p.fields.eacd = {};
    EXPECT_THROW(renderCpu(p, cam, unshaded(Caster::EACD)), InputError);
    // Trilinear leaping needs a volume segmented for it.
    RenderSettings tri = unshaded(Caster::ACD);
    tri.trilinear = true;
    EXPECT_THROW(renderCpu(p, cam, tri), InputError);
    p.meta.segmentation.trilinear = true;
    EXPECT_NO_THROW(renderCpu(p, cam, tri));
    // Scalars or a table that do not fit.
    PreparedVolume noTable = constantVolume({4, 4, 4}, 0.1);
    noTable.classification.table = {};
    EXPECT_THROW(renderCpu(noTable, cam, unshaded(Caster::Primitive)), InputError);
    PreparedVolume fewScalars = constantVolume({4, 4, 4}, 0.1);
    fewScalars.scalars.values.pop_back();
    EXPECT_THROW(renderCpu(fewScalars, cam, unshaded(Caster::Primitive)), InputError);
}

// Fields built for some octants only: a ray in another octant steps sample by sample, so the image is the one of
// the full fields, at more iterations there.
TEST(RenderCpuRenderer, ARayInAnOctantWithoutItsFieldStepsSampleBySample) {
    const PreparedVolume full = constantVolume({12, 12, 12}, 0.01);
    auto camera = [&](double azimuth) {
        ViewParams v = axisView(16);
        v.azimuthDeg = azimuth;
        v.elevationDeg = 20;
        return Camera::fit(full.grid(), v);
    };
    const unsigned held = viewOctants(camera(30));  // orthographic: one octant
    PreparedVolume some = full;
    for (int o = 0; o < kOctants; ++o)
        if (!(held >> o & 1u)) {
            some.fields.acd[o] = {};
            some.fields.eacd[o] = {};
        }
    const auto fetches = [](const RenderResult& r) {
        return std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0);
    };
    for (Caster c : {Caster::ACD, Caster::EACD}) {
        for (const double azimuth : {30.0, 210.0}) {  // the octant held, and the opposite one
            const Camera cam = camera(azimuth);
            const RenderResult a = renderCpu(full, cam, unshaded(c)), b = renderCpu(some, cam, unshaded(c));
            EXPECT_LT(maxAbsDifference(a.image, b.image), 1e-6) << casterName(c) << " " << azimuth;
            if (azimuth == 30.0) {
                EXPECT_EQ(fetches(b), fetches(a)) << casterName(c);
            } else {
                EXPECT_GT(fetches(b), fetches(a)) << casterName(c);
            }
        }
    }
}

// Post-classification: voxels at scalars 0 and 2, transparent, with a TF that is opaque at 1 only. Trilinear
// sampling interpolates the scalar, then classifies it, so the samples between the two voxels show the peak;
// nearest sampling never takes the value 1.
TEST(RenderCpuRenderer, TrilinearClassifiesTheInterpolatedScalar) {
    PreparedVolume p;
    p.scalars.grid.dims = {2, 1, 1};
    p.scalars.sourceType = ScalarType::UInt8;
    p.scalars.values = {0.f, 2.f};
    p.classification.table = tableOf({{0.0, {1, 0, 0}}, {0.5, {1, 0, 0}}, {0.0, {1, 0, 0}}});
    p.regions.dims = p.grid().dims;
    p.regions.label = {0, 1};
    p.regions.count = 2;
    // Along x through the middle of the row: samples at x = 0.25, 0.75, 1.25, 1.75.
    const Camera cam = test::orthoCamera({-1, 0.5, 0.5}, {1, 0, 0}, {0, 0, 1}, 1, 1, 0.5);
    RenderSettings s = unshaded(Caster::Primitive, 0.5);
    EXPECT_EQ(renderCpu(p, cam, s).image.pixel(0, 0)[3], 0.f);
    s.trilinear = true;
    const RenderResult r = renderCpu(p, cam, s);
    // Between the voxel centres (x = 0.5 .. 1.5) sigma rises linearly to the peak's and falls back: the samples
    // there add up to half a step of the peak's sigma, wherever the lattice puts them.
    const double want = 1 - std::exp(-extinctionFromOpacity(0.5, 1.0) * 0.5);
    EXPECT_NEAR(r.image.pixel(0, 0)[3], want, 1e-6);
    EXPECT_NEAR(r.image.pixel(0, 0)[0], want, 1e-6);  // red, premultiplied
}

// Shading takes its normal from the gradient of the scalars: a ramp along x lit from +x shows the full diffuse
// term; the same ramp under a light along y shows ambient only.
TEST(RenderCpuRenderer, NormalsComeFromTheScalarGradient) {
    PreparedVolume p;
    p.scalars.grid.dims = {4, 4, 4};
    p.scalars.sourceType = ScalarType::UInt8;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) p.scalars.values.push_back(float(x));
    p.classification.table = tableOf({{0.2, {1, 1, 1}}, {0.2, {1, 1, 1}}, {0.2, {1, 1, 1}}, {0.2, {1, 1, 1}}});
    p.meta.segmentation.useNormals = true;
    p.regions.dims = p.grid().dims;
    p.regions.label.assign(p.grid().voxels(), 0);
    p.regions.count = 1;
    const Camera cam = test::orthoCamera({2, 2, -1}, {0, 0, 1}, {0, 1, 0}, 1, 1, 0.5);
    RenderSettings s;
    s.stepVoxels = 0.5;
    const ShadingModel m;
    const double alpha = 1 - std::pow(0.8, 4);  // 8 samples of half a voxel
    for (const bool trilinear : {false, true}) {
        s.trilinear = trilinear;
        s.lightDirection = Vec3d{1, 0, 0};
        EXPECT_NEAR(renderCpu(p, cam, s).image.pixel(0, 0)[0], alpha * (m.ambient + m.diffuse), 1e-6) << trilinear;
        s.lightDirection = Vec3d{0, 1, 0};
        EXPECT_NEAR(renderCpu(p, cam, s).image.pixel(0, 0)[0], alpha * m.ambient, 1e-6) << trilinear;
    }
}

}  // namespace
}  // namespace vr
