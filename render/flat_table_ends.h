// Where a transfer table stops changing what MIP and MinIP show (docs/ALGORITHMS.md section 11). Their pixel is
// their value's entry over the background: through the entry's opacity, or opaque (a grey window). Every value at or
// above one scalar shows alike, and every value at or below another: MIP ends a ray once its maximum reaches the
// upper one and starts its maximum at the lower one (MinIP the converse), and the image is the same, bit for bit.
#pragma once

#include "core/scalar_classification.h"

namespace vr {

struct FlatTableEnds {
    // Every scalar >= above shows as the table's last entry; every scalar <= below as its first. A whole step
    // inside the run of entries that show alike, so that float's rounding of the table coordinate cannot reach the
    // entry before it.
    double above = 0, below = 0;
};

// opaque: the entries show their colour alone (a grey window), so entries alike in colour show alike; else
// entries alike in extinction and colour, or both of extinction 0 (both show the background) do.
FlatTableEnds flatTableEnds(const TransferTable& table, bool opaque);

}  // namespace vr
