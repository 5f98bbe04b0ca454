#include "volume.h"

#include "errors.h"

namespace vr {

std::string_view scalarTypeName(ScalarType t) {
    switch (t) {
        case ScalarType::UInt8: return "uint8";
        case ScalarType::Int16: return "int16";
        case ScalarType::UInt16: return "uint16";
        case ScalarType::Float32: return "float32";
    }
    return "unknown";
}

ScalarType parseScalarType(std::string_view name) {
    if (name == "uint8" || name == "u8") return ScalarType::UInt8;
    if (name == "int16" || name == "i16") return ScalarType::Int16;
    if (name == "uint16" || name == "u16") return ScalarType::UInt16;
    if (name == "float32" || name == "float" || name == "f32") return ScalarType::Float32;
    throw InputError("unknown voxel type '" + std::string(name) + "' (expected uint8, int16, uint16 or float32)");
}

}  // namespace vr
