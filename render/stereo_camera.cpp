#include "render/stereo_camera.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.h"
#include "core/number_text.h"
#include "shaders/stereo_reprojection.h"

namespace vr {

void checkStereo(double separation, std::optional<double> focus, Projection projection) {
    if (!(separation > 0) || !std::isfinite(separation))
        throw InputError("--stereo " + numberText(separation) +
                         ": the eye separation must be a positive finite distance in world units");
    if (focus && (!(*focus > 0) || !std::isfinite(*focus)))
        throw InputError("--focus " + numberText(*focus) +
                         ": the focus distance must be a positive finite distance in world units");
    if (focus && separation > *focus)
        throw InputError("--stereo " + numberText(separation) + ": the eye separation must not exceed the focus "
                         "distance --focus " + numberText(*focus));
    if (projection != Projection::Perspective)
        throw InputError("--stereo needs --projection persp: orthographic eyes see along parallel rays, which show "
                         "no depth (no disparity) between them");
}

StereoPair stereoPair(const Camera& centre, const GridGeometry& grid, double separation, std::optional<double> focus) {
    checkStereo(separation, focus, centre.projection);
    StereoPair pair;
    pair.separation = separation;
    pair.focus = focus.value_or(dot(grid.centre() - centre.eye, centre.forward));
    if (!(pair.focus > 0))
        throw InputError("--focus: the volume centre lies behind the eye; give the focus distance");
    if (separation > pair.focus)
        throw InputError("--stereo " + numberText(separation) + ": the eye separation must not exceed the focus "
                         "distance (" + numberText(pair.focus) + ", the volume centre's; --focus sets it)");
    // A point at the focus distance, x across from the centre eye, lies x + s/2 across from the left eye and x - s/2
    // from the right: shifting each window by -/+ s / (2 focus) puts it at the same pixel in both.
    pair.left = pair.right = centre;
    pair.left.eye = centre.eye - centre.right * (separation / 2);
    pair.right.eye = centre.eye + centre.right * (separation / 2);
    pair.left.shift = centre.shift + separation / (2 * pair.focus);
    pair.right.shift = centre.shift - separation / (2 * pair.focus);
    return pair;
}

double maxSpreadPixels(int height) { return kMaxSpreadPixels * std::clamp(height / 512.0, 1.0, 8.0); }

double disparityScale(const StereoPair& pair) {
    const Camera& c = pair.left;
    const double aspect = double(c.width) / double(c.height);
    return pair.separation * c.width / (2 * c.halfHeight * aspect);
}

double disparityAt(const StereoPair& pair, double depth) {
    return device::stereoDisparity(disparityScale(pair), 1 / pair.focus, depth);
}

DepthRange depthRange(const StereoPair& pair, const GridGeometry& grid) {
    const Vec3d middle = (pair.left.eye + pair.right.eye) * 0.5;
    const double centre = dot(grid.centre() - middle, pair.left.forward), radius = 0.5 * length(grid.extent());
    return {centre - radius, centre + radius};
}

}  // namespace vr
