// Extremes of the tabulated transfer function over scalar intervals (docs/ALGORITHMS.md section 9).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include "core/regions.h"
#include "preprocess/classify/transfer_function.h"

namespace vr {

// Smallest and largest opacity and colour channels over a run of table entries. Colour counts only where the
// opacity is above 0, as in the region key: a transparent entry's colour is never seen.
struct TfExtremes {
    double opacityMin = 0, opacityMax = 0;
    std::array<float, 3> colourMin{}, colourMax{};  // +inf and -inf where every entry is transparent
};

// Sparse tables over the entries of the table that classification samples: O(n log n) to build, O(1) per query.
// At most 65536 entries (classification makes no more); the constructor throws std::invalid_argument beyond.
class TfRangeTable final : public ClassificationSpread {
public:
    explicit TfRangeTable(SampledTransferFunction table);

    // Extremes over entries first .. last (first <= last < size()).
    TfExtremes entries(std::size_t first, std::size_t last) const;
    // Extremes over every entry that classifies some scalar in [lo, hi] (lo <= hi): a scalar between two entries
    // is interpolated from both (SampledTransferFunction::locate).
    TfExtremes over(double lo, double hi) const;
    uint16_t entryBelow(float f) const override;
    uint16_t entryAbove(float f) const override;
    bool alikeEntries(uint16_t first, uint16_t last, double threshold) const override;
    bool clearEntries(uint16_t first, uint16_t last) const override;

    std::size_t size() const { return table_.opacity.size(); }

private:
    SampledTransferFunction table_;
    std::vector<std::vector<TfExtremes>> levels_;  // levels_[k][i]: entries i .. i + 2^k - 1
};

}  // namespace vr
