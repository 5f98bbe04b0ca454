// Smaller copies of a volume, so that tests on the large shared datasets stay quick.
#pragma once
#include "core/volume.h"

namespace vr::test {

// The central block of at most `edge` voxels per axis, at full resolution and where it lay in the volume (its
// origin moved to the block's first voxel).
Volume centralBlock(const Volume& v, int edge);

// Every other voxel along each axis (dims halved, spacing doubled): the same extent at an eighth of the voxels.
Volume everyOtherVoxel(const Volume& v);

}  // namespace vr::test
