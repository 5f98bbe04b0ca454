// One octant of the EACD as it is stored everywhere (docs/ALGORITHMS.md section 4, storage): in memory, in the prepared
// file and on the device, each voxel's box in extentCodeBytes(code) little-endian bytes (exact: x, y, z; log16: one
// uint16; joint8: one byte). The builder writes the code straight in, so no exact copy is held beside it.
#pragma once
#include <cstdint>
#include <vector>

#include "extent_code.h"

namespace vr {

class ExtentField {
public:
    ExtentField() = default;
    // `voxels` voxels of zero bytes, for a builder or a read to fill.
    ExtentField(ExtentCode code, std::size_t voxels) : code_(code), bytes_(voxels * extentCodeBytes(code)) {}
    // Each box rounded down to the code (quantiseExtents).
    ExtentField(ExtentCode code, const std::vector<Extents>& boxes);

    ExtentCode code() const { return code_; }
    std::size_t size() const { return bytes_.size() / extentCodeBytes(code_); }
    bool empty() const { return bytes_.empty(); }
    // The box voxel v's bytes stand for.
    Extents operator[](std::size_t v) const {
        const uint8_t* b = bytes_.data() + v * extentCodeBytes(code_);
        switch (code_) {
            case ExtentCode::Exact: return {b[0], b[1], b[2]};
            case ExtentCode::Log16: return decodeExtents(code_, uint16_t(b[0] | b[1] << 8));
            case ExtentCode::Joint8: return decodeExtents(code_, b[0]);
        }
        return {1, 1, 1};
    }
    // The stored bytes, voxel after voxel: what the file and the device hold.
    uint8_t* data() { return bytes_.data(); }
    const uint8_t* data() const { return bytes_.data(); }
    std::size_t bytes() const { return bytes_.size(); }

    bool operator==(const ExtentField&) const = default;

private:
    ExtentCode code_ = ExtentCode::Exact;
    std::vector<uint8_t> bytes_;
};

}  // namespace vr
