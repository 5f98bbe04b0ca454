// What a preparation holds in memory at once, estimated before any stage runs, so that a volume too large for this
// machine is refused at once rather than killed halfway.
#pragma once
#include <cstddef>
#include <string>

#include "core/grid.h"

namespace vr {

struct PrepareOptions;

// Bytes a preparation of `grid` with `options` may hold at once: the scalars (float) and the labels throughout, and
// the larger of what segmentation adds (post-classified: footprint ranges, normal classes) and what the fields add
// (the axial runs and every field asked for, in the octants asked for). An upper estimate.
std::size_t preparationBytes(const GridGeometry& grid, const PrepareOptions& options);

// The memory available now (/proc/meminfo's MemAvailable; the physical memory where that cannot be read).
std::size_t availableMemoryBytes();

// Throws InputError naming `source` with the estimate and the limit when preparationBytes exceeds `limit` (0: the
// memory available now).
void requireWorkingSetFits(const std::string& source, const GridGeometry& grid, const PrepareOptions& options,
                           std::size_t limit);

}  // namespace vr
