// Median and nearest-rank percentiles of a sample (the figures docs/BENCH.md quotes).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

namespace vr {

// Nearest rank: the smallest value with at least q of the sample at or below it; 0 for an empty sample.
template <typename T>
double percentile(std::vector<T> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t rank = std::size_t(std::ceil(q * double(v.size())));
    return double(v[std::clamp<std::size_t>(rank, 1, v.size()) - 1]);
}

// The middle value, or the mean of the two middle ones.
inline double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace vr
