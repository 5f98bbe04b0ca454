#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "render/count_percentile.h"

namespace vr {
namespace {

// What the statistics took before: the counts sorted, the entry at index floor(fraction n).
uint32_t sortedPercentile(std::vector<uint32_t> counts, double fraction) {
    std::sort(counts.begin(), counts.end());
    return counts[std::min(counts.size() - 1, std::size_t(fraction * double(counts.size())))];
}

// Frame-like counts (many small, a few long rays) and counts larger than their number (the copy's selection) give
// the sorted entry at every fraction (1: the largest), and a frame without rays 0.
TEST(RenderCountPercentile, EqualsTheSortedCountsEntry) {
    std::mt19937 rng(7);
    for (std::size_t n : {1u, 2u, 17u, 1000u, 262144u})
        for (uint32_t spread : {1u, 60u, 5000000u}) {
            std::vector<uint32_t> counts(n);
            for (uint32_t& c : counts) c = rng() % 8 == 0 ? rng() % spread : rng() % 4;
            const std::vector<double> fractions{0.0, 0.5, 0.95, 0.999, 1.0};
            const std::vector<uint32_t> values = countPercentiles(counts, fractions);
            for (std::size_t i = 0; i < fractions.size(); ++i)
                EXPECT_EQ(values[i], sortedPercentile(counts, fractions[i]))
                    << n << " counts up to " << spread << ", fraction " << fractions[i];
            EXPECT_EQ(values.back(), *std::max_element(counts.begin(), counts.end()));
        }
    EXPECT_EQ(countPercentiles({}, {0.95, 1.0}), (std::vector<uint32_t>{0, 0}));
}

}  // namespace
}  // namespace vr
