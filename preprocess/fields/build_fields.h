// Distance fields over the regions (ALGORITHMS.md section 4). Outside the volume is never in a region.
#pragma once
#include "core/distance_fields.h"
#include "core/regions.h"

namespace vr {

std::vector<uint8_t> buildPC(const Regions& regions);
std::vector<uint8_t> buildACD(const Regions& regions, int octant);
std::vector<std::array<uint8_t, 3>> buildEACD(const Regions& regions, const std::vector<uint8_t>& acd, int octant);

// kinds: a mask of FieldKind. EACD needs ACD internally; ACD is kept only when asked for.
DistanceFields buildFields(const Regions& regions, unsigned kinds);

}  // namespace vr
