// Levoy (1988) iso-contour classification (docs/ALGORITHMS.md section 2).
#pragma once
#include <string>
#include <vector>

namespace vr {

// One iso-value f_v with width r (world units) and strength a_v in [0,1].
struct IsoContour {
    double value, width, strength;
    bool operator==(const IsoContour&) const = default;
};

// alpha = a_v (1 - |f_v - f| / (r |grad f|)) where |grad f| > 0 and |f_v - f| <= r |grad f|,
// a_v where grad f = 0 and f = f_v, else 0. `gradientMagnitude` is |grad f| per world unit.
double levoyOpacity(const IsoContour& contour, double f, double gradientMagnitude);
// Several iso-values combine as 1 - prod(1 - alpha_n).
double levoyOpacity(const std::vector<IsoContour>& contours, double f, double gradientMagnitude);

// Throws InputError naming `source` for a non-finite value, a width <= 0 or a strength outside [0,1].
void validateIsoContours(const std::vector<IsoContour>& contours, const std::string& source);

}  // namespace vr
