#include "preprocess/load/voxel_budget.h"

#include <unistd.h>

#include <climits>
#include <cstdint>
#include <string>

#include "core/errors.h"

namespace vr {

namespace {

std::size_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : SIZE_MAX;
}

}  // namespace

Vec3i checkVoxelBudget(const std::filesystem::path& path, std::int64_t nx, std::int64_t ny, std::int64_t nz,
                       std::size_t bytesPerVoxel) {
    const std::string dims = std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz);
    if (nx <= 0 || ny <= 0 || nz <= 0) throw fileError(path.string(), "dims " + dims + " must all be positive");
    if (nx > INT_MAX || ny > INT_MAX || nz > INT_MAX)
        throw fileError(path.string(), "dims " + dims + ": a dimension above " + std::to_string(INT_MAX));
    std::size_t voxels, bytes;
    if (__builtin_mul_overflow(std::size_t(nx), std::size_t(ny), &voxels) ||
        __builtin_mul_overflow(voxels, std::size_t(nz), &voxels) ||
        __builtin_mul_overflow(voxels, bytesPerVoxel, &bytes))
        throw fileError(path.string(), "dims " + dims + ": the voxel count overflows a 64-bit size");
    if (const std::size_t memory = physicalMemoryBytes(); bytes > memory)
        throw fileError(path.string(), "dims " + dims + " need " + std::to_string(bytes) +
                                           " bytes to load, more than the " + std::to_string(memory) +
                                           " bytes of memory of this machine");
    return {int(nx), int(ny), int(nz)};
}

}  // namespace vr
