#include "sweep/pareto.h"

namespace vr {

std::vector<bool> paretoFront(const std::vector<std::pair<double, double>>& points) {
    std::vector<bool> front(points.size(), true);
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t j = 0; j < points.size() && front[i]; ++j) {
            const auto& [xi, yi] = points[i];
            const auto& [xj, yj] = points[j];
            if (xj <= xi && yj <= yi && (xj < xi || yj < yi)) front[i] = false;
        }
    return front;
}

}  // namespace vr
