// What lets one header be read by the C++ compiler and by glslang: a constant, a function, a real number, a lattice
// index, a three-vector, an in-out parameter and a rounding that must not be fused, in each language. Reals are
// double in C++ (the CPU reference) and float in GLSL (the casters need no double: docs/ALGORITHMS.md section 8);
// the shared code spells no literals, which the two languages write differently, and C++ finds GLSL's built-ins
// (min, max, floor, ceil, abs, pow, ldexp, dot) under the same names.
#ifndef VR_SHARED_LANGUAGE_H
#define VR_SHARED_LANGUAGE_H

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/vec3.h"

#define VR_CONSTANT inline constexpr
#define VR_FUNCTION constexpr
#define VR_MATH_FUNCTION inline  // calls the maths library, which C++ does not evaluate at compile time
#define VR_REAL double
#define VR_INDEX std::int64_t
#define VR_VEC3 ::vr::Vec3d
#define VR_INOUT(T) T&
#define VR_PRECISE

namespace vr::device {
using std::abs;
using std::ceil;
using std::floor;
using std::ldexp;
using std::max;
using std::min;
using std::pow;
VR_CONSTANT double kInfinity = std::numeric_limits<double>::infinity();
inline double vrExpm1(double x) { return std::expm1(x); }
}  // namespace vr::device
#else
#define VR_CONSTANT const
#define VR_FUNCTION
#define VR_MATH_FUNCTION
#define VR_REAL float
#define VR_INDEX uint
#define VR_VEC3 vec3
#define VR_INOUT(T) inout T
#define VR_PRECISE precise
#endif

#endif
