#include "preprocess/classify/tf_range_table.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace vr {
namespace {

TfExtremes combined(const TfExtremes& a, const TfExtremes& b) {
    TfExtremes e{std::min(a.opacityMin, b.opacityMin), std::max(a.opacityMax, b.opacityMax), {}, {}};
    for (int c = 0; c < 3; ++c) {
        e.colourMin[c] = std::min(a.colourMin[c], b.colourMin[c]);
        e.colourMax[c] = std::max(a.colourMax[c], b.colourMax[c]);
    }
    return e;
}

}  // namespace

TfRangeTable::TfRangeTable(SampledTransferFunction table) : table_(std::move(table)) {
    const std::size_t n = table_.opacity.size();
    if (n == 0 || n > 65536)
        throw std::invalid_argument("TfRangeTable: " + std::to_string(n) + " entries, not 1..65536");
    constexpr float kInf = std::numeric_limits<float>::infinity();
    std::vector<TfExtremes> single(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double a = table_.opacity[i];
        const bool seen = a > 0;
        single[i] = {a, a, seen ? table_.colour[i] : std::array<float, 3>{kInf, kInf, kInf},
                     seen ? table_.colour[i] : std::array<float, 3>{-kInf, -kInf, -kInf}};
    }
    levels_.push_back(std::move(single));
    for (std::size_t width = 2; width <= n; width *= 2) {
        const std::vector<TfExtremes>& below = levels_.back();
        std::vector<TfExtremes> level(n - width + 1);
        for (std::size_t i = 0; i < level.size(); ++i) level[i] = combined(below[i], below[i + width / 2]);
        levels_.push_back(std::move(level));
    }
}

TfExtremes TfRangeTable::entries(std::size_t first, std::size_t last) const {
    const int k = std::bit_width(last - first + 1) - 1;
    const std::vector<TfExtremes>& level = levels_[std::size_t(k)];
    return combined(level[first], level[last + 1 - (std::size_t(1) << k)]);
}

TfExtremes TfRangeTable::over(double lo, double hi) const {
    std::size_t first, last;
    double w;
    table_.locate(lo, first, w);
    table_.locate(hi, last, w);
    return entries(first, w > 0 ? last + 1 : last);
}

uint16_t TfRangeTable::entryBelow(float f) const {
    std::size_t i;
    double w;
    table_.locate(f, i, w);
    return uint16_t(i);
}

uint16_t TfRangeTable::entryAbove(float f) const {
    std::size_t i;
    double w;
    table_.locate(f, i, w);
    return uint16_t(w > 0 ? i + 1 : i);
}

bool TfRangeTable::clearEntries(uint16_t first, uint16_t last) const { return !(entries(first, last).opacityMax > 0); }

bool TfRangeTable::alikeEntries(uint16_t first, uint16_t last, double threshold) const {
    const TfExtremes e = entries(first, last);
    if (!(e.opacityMax > 0)) return true;
    if (!(e.opacityMax - e.opacityMin <= threshold)) return false;
    for (int c = 0; c < 3; ++c)
        if (!(double(e.colourMax[c]) - e.colourMin[c] <= threshold)) return false;
    return true;
}

}  // namespace vr
