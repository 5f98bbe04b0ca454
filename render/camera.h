// The one camera convention (docs/ALGORITHMS.md section 1) for the CPU reference, the Vulkan casters and the CLI.
#pragma once
#include "core/grid.h"
#include "render/render_settings.h"

namespace vr {

struct Ray {
    Vec3d origin;     // world
    Vec3d direction;  // world, unit length
};

// Default view: from +z looking toward -z, +y up, at the volume centre; azimuth turns about up,
// elevation about right. Orthographic fits the bounding sphere; perspective puts the sphere in the fov.
struct Camera {
    Projection projection = Projection::Orthographic;
    int width = 0, height = 0;
    Vec3d eye;                 // perspective: the eye; orthographic: centre of the image plane
    Vec3d forward, right, up;  // orthonormal
    double halfHeight = 1;     // orthographic: half the image height in world units; perspective: tan(fov/2)

    static Camera fit(const GridGeometry& grid, const ViewParams& view);

    // Ray through pixel (px, py), px in [0,width) left to right, py in [0,height) top to bottom;
    // pass pixel centres (x + 0.5, y + 0.5). The centre pixel's ray passes through the volume centre.
    Ray ray(double px, double py) const;
};

}  // namespace vr
