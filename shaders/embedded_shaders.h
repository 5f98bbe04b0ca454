// SPIR-V of every shaders/*.comp, embedded at build time (shaders/CMakeLists.txt, cmake/EmbedSpirv.cmake).
#pragma once
#include <cstdint>
#include <vector>

// The casters' module for a caster and a blend (shaders/device_contract.h ids; shaders/CMakeLists.txt builds one per
// pair the renderer accepts), plain (composite without labels, stored gradients or stereo bands: caster.comp
// VR_PLAIN) or full; null for a pair without one.
const std::vector<uint32_t>* casterModule(int caster, int blend, bool plain);
extern const std::vector<uint32_t> numerics_test_spv;  // expm1 / log1p over a buffer, for the tests
extern const std::vector<uint32_t> stereo_reproject_spv;  // a stereo pair's right eye from its left eye
