#include "render/count_percentile.h"

#include <algorithm>
#include <cstddef>

namespace vr {

std::vector<uint32_t> countPercentiles(const std::vector<uint32_t>& counts, const std::vector<double>& fractions) {
    std::vector<uint32_t> values(fractions.size(), 0);
    if (counts.empty()) return values;
    const auto rankOf = [&](double fraction) {  // 1-based
        return std::min(counts.size(), std::size_t(fraction * double(counts.size())) + 1);
    };
    const uint32_t most = *std::max_element(counts.begin(), counts.end());
    if (most > counts.size()) {  // a tally longer than the counts
        std::vector<uint32_t> ranked = counts;
        for (std::size_t i = 0; i < fractions.size(); ++i) {
            const std::ptrdiff_t rank = std::ptrdiff_t(rankOf(fractions[i]));
            std::nth_element(ranked.begin(), ranked.begin() + (rank - 1), ranked.end());
            values[i] = ranked[std::size_t(rank - 1)];
        }
        return values;
    }
    std::vector<std::size_t> tally(std::size_t(most) + 1, 0);
    for (uint32_t n : counts) ++tally[n];
    for (std::size_t i = 0; i < fractions.size(); ++i) {
        const std::size_t rank = rankOf(fractions[i]);
        uint32_t value = 0;
        for (std::size_t seen = tally[0]; seen < rank;) seen += tally[++value];
        values[i] = value;
    }
    return values;
}

}  // namespace vr
