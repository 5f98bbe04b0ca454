// The Pareto front of points where smaller is better in both coordinates (time, error).
#pragma once
#include <utility>
#include <vector>

namespace vr {

// front[i] is true when no other point is at least as good in both coordinates and better in one.
// Equal points are all on the front.
std::vector<bool> paretoFront(const std::vector<std::pair<double, double>>& points);

}  // namespace vr
