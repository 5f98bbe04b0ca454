// SPIR-V of every shaders/*.comp, embedded at build time (shaders/CMakeLists.txt, cmake/EmbedSpirv.cmake).
#pragma once
#include <cstdint>
#include <vector>

extern const std::vector<uint32_t> caster_spv;         // the four casters (specialization constants)
extern const std::vector<uint32_t> numerics_test_spv;  // expm1 / log1p over a buffer, for the tests
extern const std::vector<uint32_t> stereo_reproject_spv;  // a stereo pair's right eye from its left eye
