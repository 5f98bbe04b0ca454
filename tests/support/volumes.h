// Volumes the tests make: from a function of the voxel, and smaller copies of a volume, so that tests on the large
// shared datasets stay quick.
#pragma once
#include <functional>

#include "core/volume.h"

namespace vr::test {

// A volume of `dims` and `spacing` whose voxel (x, y, z) holds f(x, y, z), called in voxel order (x fastest), as
// `type` holds it (the caller keeps integer types integral).
Volume volumeOf(Vec3i dims, Vec3d spacing, ScalarType type, const std::function<double(int, int, int)>& f);

// The central block of at most `edge` voxels per axis, at full resolution and where it lay in the volume (its
// origin moved to the block's first voxel).
Volume centralBlock(const Volume& v, int edge);

// Every other voxel along each axis (dims halved, spacing doubled): the same extent at an eighth of the voxels.
Volume everyOtherVoxel(const Volume& v);

}  // namespace vr::test
