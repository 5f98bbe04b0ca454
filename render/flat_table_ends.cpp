#include "render/flat_table_ends.h"

namespace vr {
namespace {

bool sameEntry(const TransferTable& t, std::size_t i, std::size_t j) {
    return t.sigma[i] == t.sigma[j] && t.colour[i] == t.colour[j];
}

}  // namespace

FlatTableEnds flatTableEnds(const TransferTable& table) {
    const std::size_t n = table.size();
    if (n == 0) return {};
    std::size_t first = n - 1;  // the first entry of the run that ends the table
    while (first > 0 && sameEntry(table, first - 1, n - 1)) --first;
    std::size_t last = 0;  // the last entry of the run that starts it
    while (last + 1 < n && sameEntry(table, last + 1, 0)) ++last;
    // A scalar a step past an entry of the run interpolates between two entries of it (or clamps to the end).
    return {table.lo + (double(first) + 1) * table.step, table.lo + (double(last) - 1) * table.step};
}

}  // namespace vr
