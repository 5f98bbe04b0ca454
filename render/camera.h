// The one camera convention (docs/ALGORITHMS.md section 1) for the CPU reference, the Vulkan casters and the CLI.
#pragma once
#include <vector>

#include "core/grid.h"
#include "render/render_settings.h"

namespace vr {

struct Ray {
    Vec3d origin;     // world
    Vec3d direction;  // world, unit length
};

// Bounds of ViewParams' zoom, of the angle between the up vector and the view direction (its sine), and of the
// focal point's distance from the volume centre in bounding radii: beyond them a view shows nothing or no up.
constexpr double kMinZoom = 1e-3, kMaxZoom = 1e3;
constexpr double kMinUpSine = 1e-6;
constexpr double kMaxCentreRadii = 1000;

// The checks of a view that need no volume: size, field of view, angles, zoom, an up along the view direction.
// InputError naming the flag (--fov, --zoom, --up, ...).
void checkView(const ViewParams& view);

// Default view: from +z looking toward -z, +y up, at the volume centre; azimuth turns about up,
// elevation about right. Orthographic fits the bounding sphere; perspective puts the sphere in the fov.
// ViewParams' up, centre, zoom and orbitDeg then act as VTK's camera calls of the same names.
struct Camera {
    Projection projection = Projection::Orthographic;
    int width = 0, height = 0;
    Vec3d eye;                 // perspective: the eye; orthographic: centre of the image plane
    Vec3d forward, right, up;  // orthonormal
    double halfHeight = 1;     // orthographic: half the image height in world units; perspective: tan(fov/2)
    double shift = 0;          // perspective: the image window's horizontal offset in units of the image plane at
                               // distance 1 (an off-axis stereo eye, render/stereo_camera.h); 0: centred

    static Camera fit(const GridGeometry& grid, const ViewParams& view);
    // The views of an orbit: view i turned 360 i / views degrees about the view-up from `view`.
    static std::vector<Camera> orbit(const GridGeometry& grid, const ViewParams& view, int views);

    // Ray through pixel (px, py), px in [0,width) left to right, py in [0,height) top to bottom;
    // pass pixel centres (x + 0.5, y + 0.5). The centre pixel's ray passes through the volume centre.
    Ray ray(double px, double py) const;
};

}  // namespace vr
