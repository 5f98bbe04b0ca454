// EACD extents as the device holds them (core/extent_code.h): exact bytes, or a code decoded through the table
// that extentDecodeTable() states in C++ and the renderer uploads (never retyped here).
#ifndef VR_EXTENT_CODE_GLSL
#define VR_EXTENT_CODE_GLSL

#include "device_contract.h"

layout(constant_id = kSpecIdExtentCode) const int EACD_CODE = kExact;  // kExact (RGBA8), kLog16 (R16), kJoint8 (R8)

// Log16: entry i < 32 is the value of the 5-bit index i (x, y, z alike). Joint8: entry i is box i.
layout(set = 0, binding = kBindingExtentTable, std140) uniform ExtentTable { uvec4 extentTable[kExtentTableEntries]; };

// The box extents of one texel of the EACD image (at least 1 each: a stored 0 would be a corrupt field).
ivec3 decodeExtents(uvec4 texel) {
    uvec3 e = texel.rgb;
    if (EACD_CODE == kLog16) {
        uint c = texel.r;
        e = uvec3(extentTable[c & 31u].x, extentTable[(c >> 5) & 31u].y, extentTable[(c >> 10) & 31u].z);
    } else if (EACD_CODE == kJoint8) {
        e = extentTable[texel.r & 255u].xyz;
    }
    return max(ivec3(1), ivec3(e));
}

#endif
