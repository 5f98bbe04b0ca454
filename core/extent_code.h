// Compact codes for EACD box extents (docs/ALGORITHMS.md section 4, storage). A code rounds every extent DOWN to a
// value it can hold, so a coded box lies inside the exact one and stays homogeneous: leaps stay conservative and
// only get shorter. The EACD builder writes the code as it goes (extent_field.h), so memory, the prepared file and
// the device all hold the same bytes and the CPU reference renders what the GPU renders.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace vr {

struct DistanceFields;

enum class ExtentCode : uint8_t {
    Exact,   // one byte per axis (3 per octant)
    Log16,   // 5 bits per axis in a uint16 per octant: 1..16 exactly, then geometric (ratio ~1.19) up to 255
    Joint8,  // one byte per octant: an index into a table of box shapes (6 levels per axis, 216 boxes)
};

// What volprep and the benchmarks store unless told otherwise.
constexpr ExtentCode kDefaultExtentCode = ExtentCode::Log16;

using Extents = std::array<uint8_t, 3>;

// One entry of the decode table as the shader reads it (a std140 uvec4; w unused).
using ExtentTableEntry = std::array<uint32_t, 4>;
constexpr int kExtentTableEntries = 256;
using ExtentTable = std::array<ExtentTableEntry, kExtentTableEntries>;

std::string_view extentCodeName(ExtentCode code);  // "exact", "log16", "joint8"
// Throws InputError naming `what` (a flag or a file) for an unknown name.
ExtentCode parseExtentCode(std::string_view name, std::string_view what);

// Stored bytes per voxel and octant: 3 (exact), 2 (log16), 1 (joint8).
constexpr std::size_t extentCodeBytes(ExtentCode code) {
    return code == ExtentCode::Exact ? 3 : code == ExtentCode::Log16 ? 2 : 1;
}

// Every code is a sum of one term per axis (exact: byte a; log16: 5 bits at 5a; joint8: a level times 6^a): the
// term of extent 0..255 on each axis, that extent rounded down to a value the code holds.
using ExtentCodeTerms = std::array<std::array<uint32_t, 256>, 3>;
const ExtentCodeTerms& extentCodeTerms(ExtentCode code);
// The code of the largest box the code holds inside extents (each >= 1): the sum of the axes' terms.
uint32_t encodeExtents(ExtentCode code, const Extents& extents);
// The extents a code stands for. Log16 and Joint8 only.
Extents decodeExtents(ExtentCode code, uint16_t coded);
// decode(encode(extents)): each axis rounded down to the code's values (Exact: unchanged).
Extents quantiseExtents(ExtentCode code, const Extents& extents);

// How the shader decodes (the only statement of the code's values; handed to the shader as a uniform buffer).
// Log16: entry i (i < 32) holds the value of 5-bit index i in x, y and z; the axes are bits 0-4, 5-9, 10-14.
// Joint8: entry i holds the box (x, y, z) of index i. Entries no code uses hold the 1-voxel box.
// Exact: unused (all 1-voxel boxes).
const ExtentTable& extentDecodeTable(ExtentCode code);

// Recodes every EACD octant to `code`, each box rounded down to it.
void quantiseEACD(DistanceFields& fields, ExtentCode code);

}  // namespace vr
