// The camera convention (docs/ALGORITHMS.md section 1): default view, azimuth / elevation, fit, anisotropic grids.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "render/camera.h"
#include "render/ray_setup.h"
#include "support/views.h"

namespace vr {
namespace {

GridGeometry boxGrid() {
    GridGeometry g;
    g.dims = {10, 20, 30};
    g.spacing = {1, 1, 1};
    g.origin = {-3, 4, 7};
    return g;
}

ViewParams view(Projection p, int w, int h, double az = 0, double el = 0) { return test::orbitView(az, el, w, h, p); }

double distanceToRay(const Vec3d& p, const Ray& r) { return length(cross(p - r.origin, r.direction)); }

void expectNear(const Vec3d& a, const Vec3d& b, double tol = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(RenderCamera, DefaultLooksDownMinusZWithYUp) {
    for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
        const Camera cam = Camera::fit(boxGrid(), view(p, 64, 48));
        expectNear(cam.forward, {0, 0, -1});
        expectNear(cam.up, {0, 1, 0});
        expectNear(cam.right, {1, 0, 0});
        EXPECT_GT(cam.eye.z, boxGrid().centre().z + 0.5 * length(boxGrid().extent()));
        // Exactly axis-aligned: the other components are zero, so the ray setup sees d_a == 0.
        EXPECT_EQ(cam.forward.x, 0.0);
        EXPECT_EQ(cam.forward.y, 0.0);
        // Pixel (0,0) is top-left: its ray is left of and above the centre.
        const Ray r = cam.ray(0.5, 0.5);
        const Vec3d towardPixel = (p == Projection::Orthographic) ? r.origin - cam.eye : r.direction;
        EXPECT_LT(dot(towardPixel, cam.right), 0);
        EXPECT_GT(dot(towardPixel, cam.up), 0);
    }
}

TEST(RenderCamera, AzimuthAndElevationMoveTheEyeLikeVtk) {
    const GridGeometry g = boxGrid();
    const Vec3d c = g.centre();
    // Positive azimuth moves the camera toward +x, positive elevation toward +y.
    const Camera az = Camera::fit(g, view(Projection::Perspective, 32, 32, 30, 0));
    EXPECT_GT(az.eye.x, c.x);
    EXPECT_NEAR(az.eye.y, c.y, 1e-9);
    const Camera el = Camera::fit(g, view(Projection::Perspective, 32, 32, 0, 30));
    EXPECT_GT(el.eye.y, c.y);
    EXPECT_NEAR(el.eye.x, c.x, 1e-9);

    // Multiples of 90 degrees look exactly along an axis.
    const Camera a90 = Camera::fit(g, view(Projection::Orthographic, 32, 32, 90, 0));
    EXPECT_EQ(a90.forward.x, -1.0);
    EXPECT_EQ(a90.forward.y, 0.0);
    EXPECT_EQ(a90.forward.z, 0.0);
    expectNear(a90.up, {0, 1, 0}, 0);
    const Camera e90 = Camera::fit(g, view(Projection::Orthographic, 32, 32, 0, 90));
    EXPECT_EQ(e90.forward.y, -1.0);
    EXPECT_EQ(e90.forward.x, 0.0);
    EXPECT_EQ(e90.forward.z, 0.0);
    const Camera a270 = Camera::fit(g, view(Projection::Orthographic, 32, 32, -90, 0));
    EXPECT_EQ(a270.forward.x, 1.0);
    const Camera a180 = Camera::fit(g, view(Projection::Orthographic, 32, 32, 540, 0));
    EXPECT_EQ(a180.forward.z, 1.0);

    // Any angles: an orthonormal right-handed frame, the eye on the -forward side.
    for (double azDeg : {-170.0, -33.3, 12.5, 95.0, 181.0})
        for (double elDeg : {-80.0, -10.0, 0.0, 45.0, 89.0}) {
            const Camera cam = Camera::fit(g, view(Projection::Perspective, 16, 16, azDeg, elDeg));
            EXPECT_NEAR(length(cam.forward), 1, 1e-12);
            EXPECT_NEAR(length(cam.up), 1, 1e-12);
            EXPECT_NEAR(dot(cam.forward, cam.up), 0, 1e-12);
            expectNear(cross(cam.forward, cam.up), cam.right);
            EXPECT_GT(dot(c - cam.eye, cam.forward), 0);
        }
}

TEST(RenderCamera, CentreRayPassesThroughTheVolumeCentre) {
    const GridGeometry g = boxGrid();
    for (Projection p : {Projection::Orthographic, Projection::Perspective})
        for (double azDeg : {0.0, 37.0, 200.0})
            for (double elDeg : {0.0, -23.0, 61.0}) {
                // Odd size: the centre pixel's ray; even size: the ray through the image centre.
                const Camera odd = Camera::fit(g, view(p, 33, 21, azDeg, elDeg));
                EXPECT_NEAR(distanceToRay(g.centre(), odd.ray(16 + 0.5, 10 + 0.5)), 0, 1e-9);
                const Camera even = Camera::fit(g, view(p, 32, 20, azDeg, elDeg));
                EXPECT_NEAR(distanceToRay(g.centre(), even.ray(16, 10)), 0, 1e-9);
                EXPECT_NEAR(length(even.ray(3.5, 7.5).direction), 1, 1e-12);
            }
}

TEST(RenderCamera, OrthographicFitsTheBoundingSphere) {
    const GridGeometry g = boxGrid();
    const double radius = 0.5 * length(g.extent());
    // Wide image: the sphere touches the top and bottom edges, the left/right edges are farther out.
    Camera wide = Camera::fit(g, view(Projection::Orthographic, 80, 40, 25, 15));
    EXPECT_NEAR(distanceToRay(g.centre(), wide.ray(40, 0)), radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), wide.ray(40, 40)), radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), wide.ray(0, 20)), 2 * radius, 1e-9);
    // Corner rays of a square view pass at sqrt(2) radius; every ray is parallel to forward.
    Camera square = Camera::fit(g, view(Projection::Orthographic, 50, 50, -40, 70));
    EXPECT_NEAR(distanceToRay(g.centre(), square.ray(0, 0)), std::sqrt(2.0) * radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), square.ray(50, 50)), std::sqrt(2.0) * radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), square.ray(0, 25)), radius, 1e-9);
    expectNear(square.ray(0, 0).direction, square.forward, 0);
    // Tall image: the sphere touches the left and right edges.
    Camera tall = Camera::fit(g, view(Projection::Orthographic, 30, 90));
    EXPECT_NEAR(distanceToRay(g.centre(), tall.ray(0, 45)), radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), tall.ray(15, 0)), 3 * radius, 1e-9);
    // The image plane starts outside the sphere, so every ray enters the volume at t > 0.
    EXPECT_GT(dot(g.centre() - square.eye, square.forward), radius);
}

TEST(RenderCamera, PerspectiveFitsTheBoundingSphereInTheFieldOfView) {
    const GridGeometry g = boxGrid();
    const double radius = 0.5 * length(g.extent());
    ViewParams v = view(Projection::Perspective, 64, 64, 15, -20);
    v.fovDeg = 40;
    const Camera cam = Camera::fit(g, v);
    EXPECT_NEAR(length(cam.eye - g.centre()), radius / std::sin(20 * std::numbers::pi / 180), 1e-9);
    EXPECT_NEAR(cam.halfHeight, std::tan(20 * std::numbers::pi / 180), 1e-12);
    // The rays through the middles of the edges are tangent to the sphere.
    EXPECT_NEAR(distanceToRay(g.centre(), cam.ray(32, 0)), radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), cam.ray(0, 32)), radius, 1e-9);
    EXPECT_NEAR(distanceToRay(g.centre(), cam.ray(64, 32)), radius, 1e-9);
    // The vertical angle between the top and bottom edge rays is the field of view.
    const double angle = std::acos(dot(cam.ray(32, 0).direction, cam.ray(32, 64).direction));
    EXPECT_NEAR(angle, 40 * std::numbers::pi / 180, 1e-12);
    // A tall image: the narrower horizontal angle decides the distance, so the sphere still fits.
    ViewParams tallView = view(Projection::Perspective, 32, 64);
    const Camera tall = Camera::fit(g, tallView);
    EXPECT_NEAR(distanceToRay(g.centre(), tall.ray(0, 32)), radius, 1e-9);
    EXPECT_GT(distanceToRay(g.centre(), tall.ray(16, 0)), radius);
}

TEST(RenderCamera, AnisotropicSpacing) {
    GridGeometry g;
    g.dims = {64, 64, 20};
    g.spacing = {0.5, 0.5, 2.5};
    g.origin = {10, -5, 3};
    const double radius = 0.5 * length(Vec3d{32, 32, 50});
    const Camera cam = Camera::fit(g, view(Projection::Orthographic, 41, 41));
    EXPECT_NEAR(cam.halfHeight, radius, 1e-12);
    const Ray centre = cam.ray(20.5, 20.5);
    EXPECT_NEAR(distanceToRay(g.centre(), centre), 0, 1e-9);
    // In grid space the centre ray runs down the middle of the grid along -z, t still in world units.
    const GridRay gr = toGridRay(centre, g);
    EXPECT_NEAR(gr.o.x, 32, 1e-9);
    EXPECT_NEAR(gr.o.y, 32, 1e-9);
    EXPECT_EQ(gr.d.z, -1 / 2.5);
    const RayInterval iv = intersectGrid(gr, g.dims);
    EXPECT_NEAR(iv.tExit - iv.tEntry, 50, 1e-9);  // the world depth of the volume
}

TEST(RenderCamera, RejectsBadViews) {
    EXPECT_THROW(Camera::fit(boxGrid(), view(Projection::Orthographic, 0, 10)), InputError);
    ViewParams v = view(Projection::Perspective, 10, 10);
    v.fovDeg = 180;
    EXPECT_THROW(Camera::fit(boxGrid(), v), InputError);
    EXPECT_THROW(Camera::fit(boxGrid(), view(Projection::Perspective, 10, 10, std::nan(""), 0)), InputError);
}

// --up as VTK's SetViewUp then OrthogonalizeViewUp: the view direction stays, the image turns about it.
TEST(RenderCamera, UpTurnsTheImageAboutTheViewDirection) {
    const GridGeometry g = boxGrid();
    for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
        ViewParams v = view(p, 33, 21, 40, 25);
        const Camera plain = Camera::fit(g, v);
        v.up = Vec3d{0, 1, 0};  // +y, the default's own: the same camera
        const Camera same = Camera::fit(g, v);
        expectNear(same.up, plain.up);
        expectNear(same.eye, plain.eye);
        v.up = Vec3d{1, 2, 0};
        const Camera turned = Camera::fit(g, v);
        expectNear(turned.forward, plain.forward, 0);
        expectNear(turned.eye, plain.eye, 0);
        EXPECT_NEAR(dot(turned.up, turned.forward), 0, 1e-12);
        EXPECT_NEAR(length(turned.up), 1, 1e-12);
        expectNear(cross(turned.forward, turned.up), turned.right);
        // up lies in the plane of the given vector and the view direction, on the given vector's side.
        EXPECT_NEAR(dot(cross(Vec3d{1, 2, 0}, turned.forward), turned.up), 0, 1e-12);
        EXPECT_GT(dot(turned.up, Vec3d{1, 2, 0}), 0);
        EXPECT_NEAR(distanceToRay(g.centre(), turned.ray(16.5, 10.5)), 0, 1e-9);
    }
    // The default view with +x up: the image is turned a quarter, exactly.
    ViewParams v = view(Projection::Orthographic, 16, 16);
    v.up = Vec3d{3, 0, 0};
    const Camera quarter = Camera::fit(g, v);
    EXPECT_EQ(quarter.up, (Vec3d{1, 0, 0}));
    EXPECT_EQ(quarter.right, (Vec3d{0, -1, 0}));
}

// The views of an orbit turn about the view-up through the focal point: about +y by default (a change of azimuth,
// bit for bit), about --up when given.
TEST(RenderCamera, OrbitTurnsAboutTheViewUp) {
    const GridGeometry g = boxGrid();
    const ViewParams plain = view(Projection::Perspective, 24, 16, 10, 30);
    const std::vector<Camera> around = Camera::orbit(g, plain, 8);
    ASSERT_EQ(around.size(), 8u);
    for (int i = 0; i < 8; ++i) {
        const Camera byAzimuth = Camera::fit(g, view(Projection::Perspective, 24, 16, 10 + 45.0 * i, 30));
        EXPECT_EQ(around[i].eye, byAzimuth.eye);
        EXPECT_EQ(around[i].forward, byAzimuth.forward);
        EXPECT_EQ(around[i].up, byAzimuth.up);
    }
    // A volume with z up, seen from the front and turned about z: every view looks level, with z up exactly.
    ViewParams zUp = view(Projection::Orthographic, 24, 16, 0, -90);
    zUp.up = Vec3d{0, 0, 1};
    const std::vector<Camera> level = Camera::orbit(g, zUp, 4);
    const Vec3d c = g.centre();
    const double distance = length(level[0].eye - c);
    const Vec3d forwards[] = {{0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}};
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(level[i].up, (Vec3d{0, 0, 1})) << i;
        expectNear(level[i].forward, forwards[i]);
        EXPECT_NEAR(length(level[i].eye - c), distance, 1e-9);
        EXPECT_NEAR(distanceToRay(c, level[i].ray(12, 8)), 0, 1e-9);
    }
    // Tilted: the eye keeps its angle to the up vector all round.
    ViewParams tilted = view(Projection::Perspective, 16, 16, 20, 10);
    tilted.up = normalize(Vec3d{1, 1, 0});
    for (const Camera& cam : Camera::orbit(g, tilted, 7))
        EXPECT_NEAR(dot(cam.forward, *tilted.up), dot(Camera::fit(g, tilted).forward, *tilted.up), 1e-12);
}

// --zoom as VTK's Zoom: the eye stays; orthographic divides the parallel scale, perspective the view angle.
TEST(RenderCamera, ZoomMagnifiesWithoutMovingTheEye) {
    const GridGeometry g = boxGrid();
    ViewParams o = view(Projection::Orthographic, 40, 30, 15, 5);
    const Camera ortho = Camera::fit(g, o);
    o.zoom = 2.5;
    const Camera orthoZoomed = Camera::fit(g, o);
    EXPECT_EQ(orthoZoomed.eye, ortho.eye);
    EXPECT_DOUBLE_EQ(orthoZoomed.halfHeight, ortho.halfHeight / 2.5);

    ViewParams p = view(Projection::Perspective, 40, 40, -30, 20);
    p.fovDeg = 40;
    const Camera persp = Camera::fit(g, p);
    p.zoom = 4;
    const Camera perspZoomed = Camera::fit(g, p);
    EXPECT_EQ(perspZoomed.eye, persp.eye);
    const double angle = std::acos(dot(perspZoomed.ray(20, 0).direction, perspZoomed.ray(20, 40).direction));
    EXPECT_NEAR(angle, 10 * std::numbers::pi / 180, 1e-12);
    p.zoom = 0.5;  // zoomed out: 80 degrees
    EXPECT_NEAR(std::acos(dot(Camera::fit(g, p).ray(20, 0).direction, Camera::fit(g, p).ray(20, 40).direction)),
                80 * std::numbers::pi / 180, 1e-12);
}

// --center: the centre pixel looks at it; an orthographic image plane stays outside the bounding sphere.
TEST(RenderCamera, CenterIsTheFocalPoint) {
    const GridGeometry g = boxGrid();
    const double radius = 0.5 * length(g.extent());
    for (Projection p : {Projection::Orthographic, Projection::Perspective})
        for (const Vec3d& focus : {Vec3d{0, 0, 0}, Vec3d{-3, 4, 7}, g.centre() + Vec3d{40, -25, 60}}) {
            ViewParams v = view(p, 33, 21, 70, -35);
            v.centre = focus;
            const Camera cam = Camera::fit(g, v);
            EXPECT_NEAR(distanceToRay(focus, cam.ray(16.5, 10.5)), 0, 1e-9);
            expectNear(cam.forward, Camera::fit(g, view(p, 33, 21, 70, -35)).forward, 0);
            if (p == Projection::Orthographic) {
                EXPECT_GT(dot(g.centre() - cam.eye, cam.forward), radius);
            }
        }
}

TEST(RenderCamera, RejectsBadUpZoomAndCenter) {
    const GridGeometry g = boxGrid();
    auto refusal = [&](const ViewParams& v) {
        try {
            Camera::fit(g, v);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    ViewParams v = view(Projection::Perspective, 16, 16);
    for (const Vec3d& up : {Vec3d{0, 0, 1}, Vec3d{0, 0, -7}, Vec3d{0, 1e-9, 1}, Vec3d{0, 0, 0},
                            Vec3d{std::nan(""), 1, 0}, Vec3d{0, double(INFINITY), 0}}) {
        v.up = up;
        EXPECT_NE(refusal(v).find("--up"), std::string::npos) << refusal(v);
    }
    v.up = Vec3d{0, 0, 1};
    v.elevationDeg = 90;  // the same up is fine once the view looks down another axis
    EXPECT_EQ(refusal(v), "accepted");
    v = view(Projection::Perspective, 16, 16);
    for (double zoom : {0.0, -1.0, std::nan(""), double(INFINITY), 1e-4, 1e4, 0.1 /* 30 / 0.1 = 300 degrees */}) {
        v.zoom = zoom;
        EXPECT_NE(refusal(v).find("--zoom"), std::string::npos) << zoom << ": " << refusal(v);
    }
    v = view(Projection::Orthographic, 16, 16);
    v.zoom = 0.1;  // no angle to exceed
    EXPECT_EQ(refusal(v), "accepted");
    for (const Vec3d& far : {Vec3d{1e9, 0, 0}, Vec3d{0, std::nan(""), 0}, Vec3d{0, 0, -double(INFINITY)}}) {
        v.centre = far;
        EXPECT_NE(refusal(v).find("--center"), std::string::npos) << refusal(v);
    }
}

}  // namespace
}  // namespace vr
