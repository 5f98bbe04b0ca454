// Synthetic volumes of any size and spacing, for tests and benchmarks: each stresses one thing
// (nothing to segment, smooth gradients, nested surfaces, worst-case fragmentation, no structure, blocks).
#pragma once
#include <cstdint>

#include "core/volume.h"

namespace vr {

// Every voxel equal: one region, the longest leaps.
Volume constantPhantom(Vec3i dims, float value = 100, Vec3d spacing = {1, 1, 1});

// Linear ramp from `from` (first slice) to `to` (last slice) along `axis` (0 = x, 1 = y, 2 = z).
Volume rampPhantom(Vec3i dims, int axis, float from = 0, float to = 255, Vec3d spacing = {1, 1, 1});

// "CT-like" concentric spherical shells in Hounsfield units: air (-1000) outside, a skin of soft tissue (40),
// a bone shell (1000) and soft tissue inside it, centred and sized relative to the physical extent.
Volume shellsPhantom(Vec3i dims, Vec3d spacing = {1, 1, 1});

// 1-voxel checkerboard of `low` and `high`: no two face neighbours alike.
Volume checkerboardPhantom(Vec3i dims, float low = 0, float high = 255, Vec3d spacing = {1, 1, 1});

// Independent uniform integers in [low, high], reproducible from `seed`.
Volume noisePhantom(Vec3i dims, uint32_t seed, int low = 0, int high = 255, Vec3d spacing = {1, 1, 1});

// A small "engine-like" part: an axis-aligned block with a bore and ribs, in uint8 values (air 0, metal 200/255).
Volume enginePhantom(Vec3i dims, Vec3d spacing = {1, 1, 1});

}  // namespace vr
