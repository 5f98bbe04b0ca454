#include "render/count_percentile.h"

#include <algorithm>
#include <cstddef>

namespace vr {

uint32_t countPercentile(const std::vector<uint32_t>& counts, double fraction) {
    if (counts.empty()) return 0;
    const std::size_t rank = std::min(counts.size(), std::size_t(fraction * double(counts.size())) + 1);  // 1-based
    const uint32_t most = *std::max_element(counts.begin(), counts.end());
    if (most > counts.size()) {  // a tally longer than the counts
        std::vector<uint32_t> ranked = counts;
        std::nth_element(ranked.begin(), ranked.begin() + std::ptrdiff_t(rank - 1), ranked.end());
        return ranked[rank - 1];
    }
    std::vector<std::size_t> tally(std::size_t(most) + 1, 0);
    for (uint32_t n : counts) ++tally[n];
    uint32_t value = 0;
    for (std::size_t seen = tally[0]; seen < rank;) seen += tally[++value];
    return value;
}

}  // namespace vr
