#include "io/prepared_checks.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace vr::prepared_detail {

std::string floatText(double v) {
    std::ostringstream s;
    s.precision(std::numeric_limits<float>::max_digits10);
    s << v;
    return s.str();
}

std::optional<std::string> tableEntryProblem(const TransferTable& t) {
    for (std::size_t i = 0; i < t.size(); ++i) {
        const auto& c = t.colour[i];
        if (!(std::isfinite(t.sigma[i]) && t.sigma[i] >= 0))
            return "transfer table entry " + std::to_string(i) + " has sigma " + floatText(t.sigma[i]) +
                   " (must be finite and >= 0)";
        if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
            return "transfer table entry " + std::to_string(i) + " has a colour that is not finite";
    }
    return std::nullopt;
}

std::optional<std::string> labelClassProblem(const LabelClasses& c) {
    for (std::size_t i = 0; i < c.size(); ++i)
        if (!(std::isfinite(c.sigma[i]) && c.sigma[i] >= 0) || !std::isfinite(c.colour[i][0]) ||
            !std::isfinite(c.colour[i][1]) || !std::isfinite(c.colour[i][2]))
            return "label " + std::to_string(i) + "'s class has a sigma that is not finite and >= 0 or a colour that "
                   "is not finite";
    return std::nullopt;
}

std::optional<std::string> classificationProblem(const ScalarClassification& c) {
    const TransferTable& t = c.table;
    if (!(std::isfinite(c.referenceStep) && c.referenceStep > 0)) return "'referenceStep' must be a finite number > 0";
    if (!(std::isfinite(c.flatGradient) && c.flatGradient >= 0)) return "'flatGradient' must be a finite number >= 0";
    if (!std::isfinite(t.lo)) return "'transferTable.lo' must be a finite number";
    if (!(std::isfinite(t.step) && t.step > 0)) return "'transferTable.step' must be a finite number > 0";
    if (!std::isfinite(t.lo + t.step * double(t.size() == 0 ? 0 : t.size() - 1)))
        return "'transferTable' ends at a scalar that is not finite";
    return std::nullopt;
}

}  // namespace vr::prepared_detail
