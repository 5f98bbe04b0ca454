// Stereo pairs' cameras (render/stereo_camera.h): two parallel perspective eyes the separation apart, whose off-axis
// windows meet at the focus distance; the disparity the reprojection moves a point by (shaders/stereo_reprojection.h)
// against the pixels the two cameras' rays put it at; the refusals of bad separations and focus distances.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "render/stereo_camera.h"
#include "support/views.h"

namespace vr {
namespace {

const GridGeometry kGrid{{40, 30, 20}, {1, 1.5, 2}, {-5, 3, 7}};

// The pixel coordinates (x + 0.5 at a pixel's centre) where a perspective camera sees world point p, and its depth
// along the view direction.
struct Projected {
    double x, y, depth;
};
Projected project(const Camera& c, const Vec3d& p) {
    const Vec3d d = p - c.eye;
    const double depth = dot(d, c.forward), aspect = double(c.width) / c.height;
    const double u = dot(d, c.right) / depth, v = dot(d, c.up) / depth;
    return {((u - c.shift) / (c.halfHeight * aspect) + 1) * c.width / 2, (1 - v / c.halfHeight) * c.height / 2, depth};
}

StereoPair pairAt(double azimuth, double elevation, double separation, std::optional<double> focus, int w = 64,
                  int h = 48) {
    const Camera centre = Camera::fit(kGrid, test::orbitView(azimuth, elevation, w, h, Projection::Perspective, 40));
    return stereoPair(centre, kGrid, separation, focus);
}

TEST(RenderStereoCamera, EyesAreParallelAndTheSeparationApart) {
    for (double azimuth : {0.0, 37.0, 200.0}) {
        const StereoPair p = pairAt(azimuth, 25, 6, std::nullopt);
        EXPECT_NEAR(length(p.right.eye - p.left.eye), 6, 1e-9);
        EXPECT_NEAR(dot(p.right.eye - p.left.eye, p.left.right), 6, 1e-9);
        EXPECT_EQ(p.left.forward, p.right.forward);
        EXPECT_EQ(p.left.up, p.right.up);
        EXPECT_GT(p.left.shift, 0);
        EXPECT_DOUBLE_EQ(p.left.shift, -p.right.shift);
        // The default focus: the volume centre's depth.
        EXPECT_NEAR(p.focus, dot(kGrid.centre() - (p.left.eye + p.right.eye) * 0.5, p.left.forward), 1e-9);
    }
}

// Each eye's rays pass through the points its projection puts at their pixels, and a point's disparity is where the
// right eye sees it minus where the left does: zero at the focus distance, on the same row always.
TEST(RenderStereoCamera, DisparityIsWhereTheEyesSeeAPoint) {
    const StereoPair p = pairAt(30, -20, 5, 60);
    int checked = 0;
    for (double depth : {35.0, 60.0, 90.0, 400.0})
        for (double across : {-9.0, 0.0, 4.0})
            for (double high : {-5.0, 3.0}) {
                const Vec3d middle = (p.left.eye + p.right.eye) * 0.5;
                const Vec3d point = middle + p.left.forward * depth + p.left.right * across + p.left.up * high;
                const Projected l = project(p.left, point), r = project(p.right, point);
                EXPECT_NEAR(l.y, r.y, 1e-9);
                EXPECT_NEAR(r.x - l.x, disparityAt(p, depth), 1e-9) << depth;
                if (depth == 60) {
                    EXPECT_NEAR(r.x - l.x, 0, 1e-9);
                }
                for (const auto& [camera, seen] : {std::pair{p.left, l}, std::pair{p.right, r}}) {
                    const Ray ray = camera.ray(seen.x, seen.y);
                    const Vec3d toPoint = point - ray.origin;
                    EXPECT_NEAR(length(cross(toPoint, ray.direction)), 0, 1e-9 * length(toPoint));
                }
                ++checked;
            }
    EXPECT_EQ(checked, 24);
    EXPECT_NEAR(disparityAt(p, INFINITY), disparityScale(p) / 60, 1e-12);
    EXPECT_LT(disparityAt(p, 30), 0);  // in front of the focus: crossed
}

// One depth stands for the same angle of disparity in every image: 3 pixels up to 512 rows, as many more pixels as
// rows beyond, up to 24 (a band's candidates in one 32-bit mask).
TEST(RenderStereoCamera, TheSpreadOneDepthStandsForGrowsWithTheRows) {
    EXPECT_EQ(maxSpreadPixels(48), kMaxSpreadPixels);
    EXPECT_EQ(maxSpreadPixels(512), kMaxSpreadPixels);
    EXPECT_EQ(maxSpreadPixels(1024), 2 * kMaxSpreadPixels);
    EXPECT_EQ(maxSpreadPixels(2048), 4 * kMaxSpreadPixels);
    EXPECT_EQ(maxSpreadPixels(16384), 8 * kMaxSpreadPixels);
}

TEST(RenderStereoCamera, DepthRangeBoundsTheVolume) {
    const StereoPair p = pairAt(10, 10, 4, std::nullopt);
    const auto [nearest, farthest] = depthRange(p, kGrid);
    const Vec3d middle = (p.left.eye + p.right.eye) * 0.5;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3d e = kGrid.extent();
        const Vec3d c = kGrid.origin + Vec3d{corner & 1 ? e.x : 0, corner & 2 ? e.y : 0, corner & 4 ? e.z : 0};
        EXPECT_GE(dot(c - middle, p.left.forward), nearest);
        EXPECT_LE(dot(c - middle, p.left.forward), farthest);
    }
}

TEST(RenderStereoCamera, BadSeparationsAndFocusDistancesAreRefused) {
    auto refused = [](double separation, std::optional<double> focus, Projection projection, const char* flag) {
        try {
            checkStereo(separation, focus, projection);
            ADD_FAILURE() << "accepted --stereo " << separation;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(flag), std::string::npos) << e.what();
        }
    };
    for (double s : {0.0, -0.0, -3.0, double(NAN), double(INFINITY)})
        refused(s, std::nullopt, Projection::Perspective, "--stereo");
    for (double f : {0.0, -1.0, double(NAN)}) refused(1, f, Projection::Perspective, "--focus");
    refused(11, 10, Projection::Perspective, "--stereo");
    refused(1, std::nullopt, Projection::Orthographic, "--projection persp");
    EXPECT_NO_THROW(checkStereo(10, 10, Projection::Perspective));
    // Larger than the default focus distance (the volume centre's): refused once it is known.
    EXPECT_THROW(pairAt(0, 0, 1e4, std::nullopt), InputError);
    EXPECT_THROW(stereoPair(Camera::fit(kGrid, test::orbitView(0, 0, 8, 8)), kGrid, 1, std::nullopt), InputError);
}

}  // namespace
}  // namespace vr
