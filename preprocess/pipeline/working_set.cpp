#include "preprocess/pipeline/working_set.h"

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <fstream>

#include "core/errors.h"
#include "core/extent_code.h"
#include "preprocess/pipeline/staged_prepare.h"

namespace vr {

std::size_t preparationBytes(const GridGeometry& grid, const PrepareOptions& options) {
    const std::size_t octants = std::size_t(std::popcount(options.octants & kAllOctants));
    // The scalars, and the region labels unless none are made (no field over them and none kept: a primitive or
    // hier render; the hier field's blocks take a few bytes per 64 voxels).
    if (!(options.fields & kRegionFields) && !options.keepRegions) return grid.voxels() * sizeof(float);
    const std::size_t held = sizeof(float) + sizeof(uint32_t);
    // Segmentation classifies each voxel as it reads it; post-classified growth keeps each voxel's footprint range,
    // its normal class (the normal's bits at T_a = 0) and whether normals mix around it.
    std::size_t segment = 0;
    if (options.segmentation.trilinear) {
        segment = 2 * sizeof(uint16_t) + 1;  // footprint entries, mixed normals
        if (options.classify.normals && options.segmentation.useNormals)
            segment += options.segmentation.angleThresholdDeg == 0 ? 12 : 4;
    }
    std::size_t fields = 0;
    // Axial runs, one byte per axis and sign (an upper bound: those read).
    if (options.fields & kRegionFields) fields += 6;
    if (options.fields & (kFieldACD | kFieldEACD | kFieldPC))
        fields += (options.fields & kFieldPC) ? kOctants : octants;  // ACD, kept or built for PC and EACD
    if (options.fields & kFieldPC) fields += 1;
    if (options.fields & kFieldEACD) fields += octants * extentCodeBytes(options.eacdCode);
    return grid.voxels() * (held + std::max(segment, fields));
}

std::size_t availableMemoryBytes() {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    std::size_t kilobytes = 0;
    while (meminfo >> key >> kilobytes) {
        if (key == "MemAvailable:") return kilobytes * 1024;
        meminfo.ignore(64, '\n');
    }
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : SIZE_MAX;
}

void requireWorkingSetFits(const std::string& source, const GridGeometry& grid, const PrepareOptions& options,
                           std::size_t limit) {
    const std::size_t needed = preparationBytes(grid, options), available = limit ? limit : availableMemoryBytes();
    if (needed <= available) return;
    char text[320];
    std::snprintf(text, sizeof text,
                  "preparing %dx%dx%d voxels needs about %.2f GiB of memory (scalars, regions, fields), more than "
                  "the %.2f GiB %s; nothing was prepared (fewer fields, --nearest or "
                  "--no-normals need less)",
                  grid.dims.x, grid.dims.y, grid.dims.z, double(needed) / (1 << 30), double(available) / (1 << 30),
                  limit ? "allowed" : "available");
    throw fileError(source, text);
}

}  // namespace vr
