// Percentiles of a frame's per-pixel counts (loop iterations per ray), for its statistics.
#pragma once
#include <cstdint>
#include <vector>

namespace vr {

// For each fraction, the count at rank min(n, floor(fraction n) + 1) of n in ascending order (0 for none): what
// sorting the counts and taking index floor(fraction n) gives, from one tally per value instead (a sort of a 512 x 512
// frame's counts took 11 ms on one core, a 2048 x 2048 one's 160 ms, for every view of an orbit); counts larger than
// n are selected on a copy. A fraction of 1 gives the largest count.
std::vector<uint32_t> countPercentiles(const std::vector<uint32_t>& counts, const std::vector<double>& fractions);

}  // namespace vr
