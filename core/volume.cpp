#include "volume.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

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

namespace {

template <typename T>
std::size_t narrowAs(const float* from, std::size_t count, unsigned char* to) {
    std::size_t firstInexact = count;
    for (std::size_t i = 0; i < count; ++i, to += sizeof(T)) {
        const float x = from[i];
        T v;
        if constexpr (std::is_floating_point_v<T>) {
            v = x;
            if (!std::isfinite(x) && firstInexact == count) firstInexact = i;
        } else {
            constexpr float lo = float(std::numeric_limits<T>::min()), hi = float(std::numeric_limits<T>::max());
            v = T(x >= lo ? (x <= hi ? x : hi) : lo);  // a NaN goes to lo, and fails the comparison below
            if (float(v) != x && firstInexact == count) firstInexact = i;
        }
        std::memcpy(to, &v, sizeof(T));
    }
    return firstInexact;
}

}  // namespace

std::size_t narrowScalars(const float* from, std::size_t count, ScalarType type, unsigned char* to) {
    switch (type) {
        case ScalarType::UInt8: return narrowAs<std::uint8_t>(from, count, to);
        case ScalarType::Int16: return narrowAs<std::int16_t>(from, count, to);
        case ScalarType::UInt16: return narrowAs<std::uint16_t>(from, count, to);
        case ScalarType::Float32: return narrowAs<float>(from, count, to);
    }
    return 0;
}

std::size_t heldVoxels(const Volume& v) {
    return v.values.empty() ? v.stored.size() / scalarBytes(v.sourceType) : v.values.size();
}

const std::vector<float>& floatValues(const Volume& v) {
    if (v.values.empty() && !v.stored.empty())
        throw std::logic_error(v.source + ": its scalars were read in their own type, for a device upload alone");
    return v.values;
}

}  // namespace vr
