// A loaded scalar volume: the one type every loader produces.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "grid.h"

namespace vr {

// The scalar type of the source file; values are held as float (exact for every integer type here).
enum class ScalarType { UInt8, Int16, UInt16, Float32 };

std::string_view scalarTypeName(ScalarType t);           // "uint8", "int16", "uint16", "float32"
ScalarType parseScalarType(std::string_view name);       // accepts those names (and "float"); throws InputError
// Bytes of one voxel of the type as stored: 1, 2, 2, 4.
constexpr std::size_t scalarBytes(ScalarType t) {
    switch (t) {
        case ScalarType::UInt8: return 1;
        case ScalarType::Int16:
        case ScalarType::UInt16: return 2;
        case ScalarType::Float32: return 4;
    }
    return 0;
}

// Writes `count` scalars held as float in type `type` at `to` (scalarBytes(type) each, unaligned), each clamped
// to the type's range and truncated toward zero; returns the index of the first one the type does not hold
// exactly (not integral, out of range or not finite), or `count` when every one is exact. How the prepared file and
// the device store a volume's scalars.
std::size_t narrowScalars(const float* from, std::size_t count, ScalarType type, unsigned char* to);

struct Volume {
    GridGeometry grid;
    ScalarType sourceType = ScalarType::Float32;
    std::vector<float> values;  // x fastest, then y, then z; size == grid.voxels(), or empty where `stored` holds them
    // The scalars in sourceType's own bytes, in the same order, instead of `values`: an integer volume read from a
    // prepared file for a device upload alone (readPrepared's PreparedReadScope::floatScalars), which copies these
    // bytes as they are; no float copy of the volume is made. Empty otherwise.
    std::vector<unsigned char> stored;
    std::string source;         // where it came from (a path), for the prepared file's metadata
    std::vector<std::string> notes;  // what loading left out, for the tools to tell the user (a 4-D file's other volumes)

    float at(int x, int y, int z) const { return values[linearIndex(grid.dims, x, y, z)]; }
};

// How many voxels' scalars the volume holds, as floats or in its own type (Volume::stored).
std::size_t heldVoxels(const Volume& v);

// The values as floats, as every reader but a device upload takes them: throws std::logic_error (a bug) where the
// volume is held in its own type alone (Volume::stored).
const std::vector<float>& floatValues(const Volume& v);

}  // namespace vr
