// C++ stand-ins for the GLSL types of shaders/device_contract.h, each aligned as std140 and std430 align it, so
// that the contract's structs have the layout glslang gives them. Only types whose std140 and C++ layouts can
// agree are offered: no three-component vectors (std140 pads them to four) and no arrays of scalars (std140
// strides them by 16).
#pragma once
#include <cstdint>

namespace vr::device {

using uint = std::uint32_t;
struct alignas(8) ivec2 {
    std::int32_t x, y;
};
struct alignas(16) ivec4 {
    std::int32_t x, y, z, w;
};
struct alignas(16) uvec4 {
    std::uint32_t x, y, z, w;
};
struct alignas(8) vec2 {
    float x, y;
};
struct alignas(16) vec4 {
    float x, y, z, w;
};

}  // namespace vr::device
