// Views and cameras for render tests: views of the orbit around a volume (fitted by Camera::fit), and exact cameras
// whose rays pass through chosen grid points.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/render_settings.h"

namespace vr::test {

// A view of the orbit around the volume, of width x height pixels.
ViewParams orbitView(double azimuthDeg, double elevationDeg, int width, int height,
                     Projection projection = Projection::Orthographic, double fovDeg = 30);

// Default settings but for the caster, shading and sampling.
RenderSettings renderSettings(Caster caster, bool shading = true, bool trilinear = false);

// Orthographic camera with a given frame; right must be unit and orthogonal to the unit forward. With odd
// width and height and halfHeight = height / 2, pixel centres sit exactly 1 world unit apart along right and up
// and the centre pixel's ray starts exactly at eye.
// Clippings of `grid` (RenderSettings' clipPlanes and crop) that every renderer faces: oblique planes through the
// volume, a crop box, both together, and the most planes allowed.
struct Clipping {
    std::string name;
    std::vector<ClipPlane> planes;
    std::optional<CropBox> crop;
    void applyTo(RenderSettings& s) const {
        s.clipPlanes = planes;
        s.crop = crop;
    }
};
std::vector<Clipping> clippings(const GridGeometry& grid);

Camera orthoCamera(const Vec3d& eye, const Vec3d& forward, const Vec3d& right, int width, int height,
                   double halfHeight);
Camera perspectiveCamera(const Vec3d& eye, const Vec3d& forward, const Vec3d& right, int width, int height,
                         double fovDeg);

}  // namespace vr::test
