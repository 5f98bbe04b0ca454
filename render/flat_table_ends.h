// Where a transfer table stops changing (docs/ALGORITHMS.md section 11): MIP ends a ray once its maximum reaches a
// scalar at or above which every value classifies alike, MinIP once its minimum reaches one at or below which they
// do. No later sample can then change what the pixel shows, so the image is the same, bit for bit.
#pragma once

#include "core/scalar_classification.h"

namespace vr {

struct FlatTableEnds {
    // Every scalar >= above classifies as the table's last entry; every scalar <= below as its first. A whole step
    // inside the flat run, so that float's rounding of the table coordinate cannot reach the entry before it.
    double above = 0, below = 0;
};

FlatTableEnds flatTableEnds(const TransferTable& table);

}  // namespace vr
