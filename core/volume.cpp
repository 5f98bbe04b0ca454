#include "volume.h"

#include "core/enum_names.h"

namespace vr {
namespace {

constexpr EnumName<ScalarType> kScalarTypeNames[] = {
    {ScalarType::UInt8, "uint8"},     {ScalarType::Int16, "int16"}, {ScalarType::UInt16, "uint16"},
    {ScalarType::Float32, "float32"}, {ScalarType::UInt8, "u8"},    {ScalarType::Int16, "i16"},
    {ScalarType::UInt16, "u16"},      {ScalarType::Float32, "float"}, {ScalarType::Float32, "f32"}};

}  // namespace

std::string_view scalarTypeName(ScalarType t) { return nameOf(kScalarTypeNames, t); }

ScalarType parseScalarType(std::string_view name) { return valueNamed(kScalarTypeNames, name, "voxel type"); }

}  // namespace vr
