// Checking a volume's size before anything is allocated for it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "core/vec3.h"

namespace vr {

// The dims of a grid of nx x ny x nz voxels that take `bytesPerVoxel` bytes of memory each while loading (what
// the file's reader holds plus the Volume's float). Throws InputError naming `path` for a dimension that is not
// positive or does not fit an int, a byte count that overflows 64 bits, or one above this machine's physical
// memory: such headers fail at once instead of in an allocation.
Vec3i checkVoxelBudget(const std::filesystem::path& path, std::int64_t nx, std::int64_t ny, std::int64_t nz,
                       std::size_t bytesPerVoxel);

}  // namespace vr
