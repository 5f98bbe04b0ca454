#include "render/flat_table_ends.h"

namespace vr {

FlatTableEnds flatTableEnds(const TransferTable& table, bool opaque) {
    const std::size_t n = table.size();
    if (n == 0) return {};
    const auto showAlike = [&](std::size_t i, std::size_t j) {
        const bool sameColour = table.colour[i] == table.colour[j];
        if (opaque) return sameColour;
        // Extinction 0 blends to extinction 0 exactly, and its colour is weighted by an opacity of 0.
        return table.sigma[i] == table.sigma[j] && (sameColour || table.sigma[i] == 0);
    };
    std::size_t first = n - 1;  // the first entry of the run that ends the table
    while (first > 0 && showAlike(first - 1, n - 1)) --first;
    std::size_t last = 0;  // the last entry of the run that starts it
    while (last + 1 < n && showAlike(last + 1, 0)) ++last;
    // A scalar a step past an entry of the run interpolates between two entries of it (or clamps to the end).
    return {table.lo + (double(first) + 1) * table.step, table.lo + (double(last) - 1) * table.step};
}

}  // namespace vr
