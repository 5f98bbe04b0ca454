// PC from the ACDs, and the driver building the requested fields.
#include <algorithm>

#include "preprocess/fields/build_fields.h"

namespace vr {

namespace {

// The centred cube of Chebyshev radius r is the union of the 8 octant cubes of edge r + 1 cornered at v,
// so pc = min over octants of acd - 1 exactly (capped at 254 because ACD caps at 255).
void lowerToACD(std::vector<uint8_t>& minACD, const std::vector<uint8_t>& acd) {
    std::transform(minACD.begin(), minACD.end(), acd.begin(), minACD.begin(),
                   [](uint8_t m, uint8_t a) { return std::min(m, a); });
}

void toRadius(std::vector<uint8_t>& minACD) {
    for (uint8_t& m : minACD) m = uint8_t(m - 1);  // every ACD is >= 1
}

}  // namespace

std::vector<uint8_t> buildPC(const Regions& regions) { return buildFields(regions, kFieldPC).pc; }

DistanceFields buildFields(const Regions& regions, unsigned kinds) {
    DistanceFields f;
    f.dims = regions.dims;
    const bool pc = kinds & kFieldPC, keepACD = kinds & (kFieldACD | kFieldEACD);
    if (!pc && !keepACD) return f;
    if (pc) f.pc.assign(voxelCount(regions.dims), uint8_t(kDistanceCap));
    std::array<std::vector<uint8_t>, kOctants> acd;
    for (int o = 0; o < kOctants; ++o) {  // one ACD at a time when only PC is asked for
        std::vector<uint8_t> a = buildACD(regions, o);
        if (pc) lowerToACD(f.pc, a);
        if (keepACD) acd[o] = std::move(a);
    }
    if (pc) toRadius(f.pc);
    if (kinds & kFieldEACD) f.eacd = buildEACD(regions, acd);
    if (kinds & kFieldACD) f.acd = std::move(acd);
    return f;
}

}  // namespace vr
