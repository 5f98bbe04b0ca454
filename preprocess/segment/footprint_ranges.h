// The scalars that trilinear sampling reads in each voxel (docs/ALGORITHMS.md section 9), as the run of transfer-table
// entries that classify them.
#pragma once
#include <cstdint>
#include <vector>

#include "core/regions.h"

namespace vr {

// Table entries lo .. hi (ClassificationSpread's entryBelow / entryAbove): four bytes per voxel.
struct EntryRange {
    uint16_t lo, hi;
};

// Per voxel, the entries that classify the scalars of its interpolation footprint, from the entry below its smallest
// scalar to the entry above its largest: the footprint is the 2x2x2 cells around every point of the voxel's cell,
// together its 3x3x3 neighbourhood, clamped at the volume's edge (cell-centred sampling). The entries are monotone
// in the scalar, so this is the entry run of the footprint's [min, max].
std::vector<EntryRange> footprintRanges(const Vec3i& dims, const std::vector<float>& scalars,
                                        const ClassificationSpread& spread);

}  // namespace vr
