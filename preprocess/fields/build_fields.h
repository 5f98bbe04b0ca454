// Distance fields over the regions (ALGORITHMS.md section 4). Outside the volume is never in a region.
// Every value is one byte; caps (all conservative: a capped box is smaller than the true one, never larger):
//   ACD  <= kDistanceCap (255): a cube edge above 255 is stored as 255.
//   PC   <= kDistanceCap - 1 (254): PC is min over octants of ACD - 1, so it inherits the ACD cap.
//   EACD <= kDistanceCap (255) per axis: the axial runs it extends with are capped at 255.
// What the cap costs: a leap is at most 255 voxels (PC: 254), so a ray through a region larger than that (the air
// of a 512^3 volume) takes a few leaps where one would do; nothing is ever wrong.
#pragma once
#include "core/distance_fields.h"
#include "core/regions.h"

namespace vr {

using EACDField = std::vector<std::array<uint8_t, 3>>;

// PC from the eight ACD passes, one at a time (no ACD is kept).
std::vector<uint8_t> buildPC(const Regions& regions);
std::vector<uint8_t> buildACD(const Regions& regions, int octant);
EACDField buildEACD(const Regions& regions, const std::vector<uint8_t>& acd, int octant);
// All eight octants at once (shares the range-minimum tables between the octants): acd[o] is buildACD(regions, o).
std::array<EACDField, kOctants> buildEACD(const Regions& regions,
                                          const std::array<std::vector<uint8_t>, kOctants>& acd);

// kinds: a mask of FieldKind. EACD needs ACD internally; ACD is kept only when asked for.
DistanceFields buildFields(const Regions& regions, unsigned kinds);

}  // namespace vr
