// Connected components of equal region keys (docs/ALGORITHMS.md section 3).
#pragma once
#include "core/regions.h"
#include "preprocess/segment/region_key.h"

namespace vr {

// 6-connected components of voxels with equal keys, labelled 0..count-1 in the order of their first voxel
// (x fastest), so the labels do not depend on how the work was split, into `regions` (the memory of its labels is
// reused). Needs fewer than 2^32 voxels.
void labelKeyComponents(const Vec3i& dims, const RegionKeyer& keyer, Regions& regions);

}  // namespace vr
