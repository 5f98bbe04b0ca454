// Distance fields over the regions (docs/ALGORITHMS.md section 4). Outside the volume is never in a region.
// Every value is one byte; caps (all conservative: a capped box is smaller than the true one, never larger):
//   ACD  <= kDistanceCap (255): a cube edge above 255 is stored as 255.
//   PC   <= kDistanceCap - 1 (254): PC is min over octants of ACD - 1, so it inherits the ACD cap.
//   EACD <= kDistanceCap (255) per axis: the axial runs it extends with are capped at 255.
// What the cap costs: a leap is at most 255 voxels (PC: 254), so a ray through a region larger than that (the air
// of a 512^3 volume) takes a few leaps where one would do; nothing is ever wrong.
#pragma once
#include <functional>

#include "core/distance_fields.h"
#include "core/progress.h"
#include "core/regions.h"
#include "preprocess/fields/axial_runs.h"

namespace vr {

using ACDFields = std::array<std::vector<uint8_t>, kOctants>;

// PC from the eight ACD passes (no ACD is kept).
std::vector<uint8_t> buildPC(const Regions& regions);
// PC from ACDs already built: one pass, pc = min over octants of acd - 1.
std::vector<uint8_t> pcFromACD(const ACDFields& acd);
std::vector<uint8_t> buildACD(const Regions& regions, int octant);
// All eight octants, in parallel, sharing the axial runs: acd[o] is buildACD(regions, o).
ACDFields buildACDs(const Regions& regions);
// In the exact code.
ExtentField buildEACD(const Regions& regions, const std::vector<uint8_t>& acd, int octant);
// All eight octants, one at a time on the same runs and working memory: acd[o] is buildACD(regions, o).
std::array<ExtentField, kOctants> buildEACD(const Regions& regions, const ACDFields& acd);

// The same builders on axial runs shared between them (each run field is computed once).
std::vector<uint8_t> buildACD(AxialRuns& runs, int octant);
// The octants of the mask (bit o: octant o), in parallel; the others stay empty.
ACDFields buildACDs(AxialRuns& runs, unsigned octants = kAllOctants);
// code: every extent written in that code, rounded down to it (quantiseExtents; Exact leaves them as built).
// octants: those to build (each needs its ACD); the others stay empty. progress: the share of octants built.
std::array<ExtentField, kOctants> buildEACD(AxialRuns& runs, const ACDFields& acd,
                                            ExtentCode code = ExtentCode::Exact, unsigned octants = kAllOctants,
                                            const Progress& progress = {});

// kinds: a mask of FieldKind. EACD needs ACD internally; ACD is kept only when asked for. The fastest way to get
// several fields: the runs, ACDs and PC are shared.
DistanceFields buildFields(const Regions& regions, unsigned kinds);
// The same, calling done(kind) as each field is finished, so that a caller can time them: ACD first (with the axial
// runs; also when it is built only for EACD), then PC (alone when only PC is asked for), then EACD.
DistanceFields buildFields(const Regions& regions, unsigned kinds, const std::function<void(FieldKind)>& done);
// The same with the EACD written in eacdCode as it is built: what quantiseEACD(buildFields(regions, kinds),
// eacdCode) gives, without an exact copy and a second pass over the extents.
// `octants` (a mask) limits ACD and EACD to the octants a render's views need; PC, which takes the minimum over all
// eight, still builds every ACD it needs. `progress` hears how far all of them have come.
DistanceFields buildFields(const Regions& regions, unsigned kinds, ExtentCode eacdCode,
                           const std::function<void(FieldKind)>& done, unsigned octants = kAllOctants,
                           const Progress& progress = {});
// The same, consuming the regions: their labels are freed as soon as the axial runs are made from them, so that
// ACD and EACD are built in 4 bytes per voxel less (a render that needs only the field).
DistanceFields buildFields(Regions&& regions, unsigned kinds, ExtentCode eacdCode,
                           const std::function<void(FieldKind)>& done, unsigned octants = kAllOctants,
                           const Progress& progress = {});

}  // namespace vr
