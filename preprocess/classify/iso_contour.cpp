#include "preprocess/classify/iso_contour.h"

#include <cmath>

#include "core/errors.h"

namespace vr {

double levoyOpacity(const IsoContour& contour, double f, double gradientMagnitude) {
    const double distance = std::abs(contour.value - f);
    if (gradientMagnitude > 0) {
        const double reach = contour.width * gradientMagnitude;
        return distance <= reach ? contour.strength * (1 - distance / reach) : 0.0;
    }
    return distance == 0 ? contour.strength : 0.0;
}

double levoyOpacity(const std::vector<IsoContour>& contours, double f, double gradientMagnitude) {
    double transmitted = 1;
    for (const IsoContour& c : contours) transmitted *= 1 - levoyOpacity(c, f, gradientMagnitude);
    return 1 - transmitted;
}

void validateIsoContours(const std::vector<IsoContour>& contours, const std::string& source) {
    for (std::size_t n = 0; n < contours.size(); ++n) {
        const IsoContour& c = contours[n];
        const std::string which = "iso-contour " + std::to_string(n) + ": ";
        if (!std::isfinite(c.value) || !std::isfinite(c.width) || !std::isfinite(c.strength))
            throw fileError(source, which + "value, width and strength must be finite numbers");
        if (!(c.width > 0)) throw fileError(source, which + "width must be > 0");
        if (!(c.strength >= 0 && c.strength <= 1)) throw fileError(source, which + "strength must be in [0,1]");
    }
}

}  // namespace vr
