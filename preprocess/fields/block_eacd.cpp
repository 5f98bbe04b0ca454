#include "preprocess/fields/block_eacd.h"

#include <stdexcept>

#include "preprocess/fields/build_fields.h"

namespace vr {

BlockEACD buildBlockEACD(const Regions& blockRegions, const std::vector<uint8_t>& homogeneous, int blockShift,
                         unsigned octants) {
    if (homogeneous.size() != blockRegions.label.size())
        throw std::invalid_argument("buildBlockEACD: the homogeneous flags do not match the blocks");
    BlockEACD h;
    h.blockShift = blockShift;
    h.blocks = blockRegions.dims;
    h.octant = buildFields(blockRegions, kFieldEACD, ExtentCode::Log16, [](FieldKind) {}, octants).eacd;
    for (ExtentField& f : h.octant) {
        uint8_t* code = f.data();  // little-endian uint16 per block
        for (std::size_t i = 0; i < f.size(); ++i, code += 2) {
            if (homogeneous[i]) code[1] |= uint8_t(kHomogeneousBlockBit >> 8);
            else code[0] = code[1] = 0;
        }
    }
    return h;
}

}  // namespace vr
