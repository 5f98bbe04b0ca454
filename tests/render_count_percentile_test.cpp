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
// the sorted entry at every fraction, and a frame without rays 0.
TEST(RenderCountPercentile, EqualsTheSortedCountsEntry) {
    std::mt19937 rng(7);
    for (std::size_t n : {1u, 2u, 17u, 1000u, 262144u})
        for (uint32_t spread : {1u, 60u, 5000000u}) {
            std::vector<uint32_t> counts(n);
            for (uint32_t& c : counts) c = rng() % 8 == 0 ? rng() % spread : rng() % 4;
            for (double fraction : {0.0, 0.5, 0.95, 0.999, 1.0})
                EXPECT_EQ(countPercentile(counts, fraction), sortedPercentile(counts, fraction))
                    << n << " counts up to " << spread << ", fraction " << fraction;
        }
    EXPECT_EQ(countPercentile({}, 0.95), 0u);
}

}  // namespace
}  // namespace vr
