// Stored gradients (docs/ALGORITHMS.md section 2, "Stored gradients"): each voxel's central-difference gradient in
// 32 bits, three 9-bit signed mantissas m under one 5-bit exponent e, g = m 2^(e + base). The volume's base puts the
// largest gradient its scalars can have at e = 31, so the 32 exponents reach 2^31 below it. The casters decode with
// unpackGradient in float, the CPU reference in double: both get the same values, which are exact in either.
// render/stored_gradients.h packs them.
#ifndef VR_GRADIENT_CODE_H
#define VR_GRADIENT_CODE_H

#include "shared_language.h"

#ifdef __cplusplus
#include "glsl_layout_types.h"
namespace vr::device {
#endif

VR_CONSTANT int kGradientMantissaMax = 255;  // the mantissas' range is symmetric: -255..255
VR_CONSTANT int kGradientExponentMax = 31;

// Mantissa of a code's 9 bits from bit `shift`, sign-extended.
VR_FUNCTION int gradientMantissa(uint code, uint shift) {
    int m = int((code >> shift) & 511u);
    return m >= 256 ? m - 512 : m;
}

// The gradient a code holds: (x, y, z) from bits 18, 9 and 0, the exponent in the top 5.
VR_MATH_FUNCTION VR_VEC3 unpackGradient(uint code, int base) {
    VR_REAL unit = ldexp(VR_REAL(1), int(code >> 27u) + base);
    return VR_VEC3(VR_REAL(gradientMantissa(code, 18u)) * unit, VR_REAL(gradientMantissa(code, 9u)) * unit,
                   VR_REAL(gradientMantissa(code, 0u)) * unit);
}

#ifdef __cplusplus
}  // namespace vr::device
#endif

#endif
