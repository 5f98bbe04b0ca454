// What lets one header be read by the C++ compiler and by glslang: a constant, a function and a real number in
// each language. Reals are double in C++ (the CPU reference) and float in GLSL (the casters need no double:
// docs/ALGORITHMS.md section 8); the shared code spells no literals, which the two languages write differently.
#ifndef VR_SHARED_LANGUAGE_H
#define VR_SHARED_LANGUAGE_H

#ifdef __cplusplus
#define VR_CONSTANT inline constexpr
#define VR_FUNCTION constexpr
#define VR_REAL double
#else
#define VR_CONSTANT const
#define VR_FUNCTION
#define VR_REAL float
#endif

#endif
