// A smaller copy of a volume for sweeps that must fit a time budget (scripts/report.sh on the largest volumes).
#pragma once
#include "core/volume.h"

namespace vr {

// Averages blocks of factor^3 voxels (the blocks at the far edges hold what is left), rounding to the nearest
// integer for integer source types so that the classification still tabulates the transfer function exactly.
// The grid keeps its origin and physical extent up to the last partial block: spacing x factor. Throws
// InputError for a factor below 1.
Volume downsample(const Volume& volume, int factor);

}  // namespace vr
