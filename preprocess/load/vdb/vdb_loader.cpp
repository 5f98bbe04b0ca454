// OpenVDB (.vdb): the first FloatGrid of the file, densified over its active voxels' bounding box.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <cstdint>
#include <mutex>

#include "core/errors.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {

Volume loadVdb(const std::filesystem::path& path) {
    static std::once_flag initialized;
    std::call_once(initialized, [] { openvdb::initialize(); });
    const auto fail = [&](const std::string& problem) { return fileError(path.string(), problem); };

    checkVdbFile(path);
    openvdb::FloatGrid::Ptr grid;
    try {
        openvdb::io::File file(path.string());
        file.open(false);  // no delayed loading: the whole grid is read anyway
        for (auto it = file.beginName(); it != file.endName() && !grid; ++it) {
            // Other grids' trees are never read: fewer bytes for OpenVDB to trust (fuzz_vdb overflowed a heap
            // buffer in an int32 tree's zipped values).
            if (!file.readGridMetadata(it.gridName())->isType<openvdb::FloatGrid>()) continue;
            grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(it.gridName()));
        }
        file.close();
    } catch (const std::exception& e) {  // openvdb::Exception, and what corrupt streams throw (bad_alloc, ...)
        throw fail(std::string("not a readable OpenVDB file: ") + e.what());
    }
    if (!grid) throw fail("holds no float grid (only FloatGrid volumes are supported)");

    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty() || grid->activeVoxelCount() == 0) throw fail("float grid '" + grid->getName() + "' is empty");
    const auto extent = [&](int a) { return std::int64_t(box.max()[a]) - box.min()[a] + 1; };  // no int overflow

    Volume v;
    v.grid.dims = checkVoxelBudget(path, extent(0), extent(1), extent(2), sizeof(float));
    // OpenVDB's CoordBBox arithmetic (the midpoint of a box copyToDense splits) overflows int beyond 2^30.
    for (int a = 0; a < 3; ++a)
        if (box.min()[a] < -(1 << 30) || box.max()[a] >= (1 << 30))
            throw fail("float grid '" + grid->getName() + "' has active voxels beyond index 2^30 (at " +
                       std::to_string(box.min()[a]) + " to " + std::to_string(box.max()[a]) + ")");
    // Memory follows the data in the file, as for the other formats. Active tiles (a constant for up to 4096^3
    // voxels in 17 bytes) and a few voxels far apart let a file of a few KiB describe a box of gigabytes (found by
    // fuzz_vdb), where stored voxels take bytes (a leaf of 512 with one active voxel about 140): beyond 16 Mi voxels,
    // a grid's box may hold at most 256 voxels per byte of the file.
    const std::uint64_t voxels = std::uint64_t(v.grid.dims.x) * v.grid.dims.y * v.grid.dims.z;
    std::error_code ec;
    const std::uint64_t fileBytes = std::filesystem::file_size(path, ec);  // checkVdbFile read it: no error
    if (voxels > std::max<std::uint64_t>(std::uint64_t(16) << 20, fileBytes * 256))
        throw fail("float grid '" + grid->getName() + "' densifies to " + std::to_string(voxels) +
                   " voxels, more than 256 per byte of its " + std::to_string(fileBytes) +
                   "-byte file (active tiles or voxels far apart)");
    v.sourceType = ScalarType::Float32;
    // VDB voxel centres lie at integer index coordinates, so the grid corner is half a voxel before the centre of
    // the bounding box's first voxel. Only the transform's scale and translation are kept (no rotation).
    const openvdb::Vec3d voxel = grid->voxelSize();
    const openvdb::Vec3d first = grid->indexToWorld(box.min());
    for (int a = 0; a < 3; ++a) {
        v.grid.spacing[a] = voxel[a];
        v.grid.origin[a] = first[a] - 0.5 * voxel[a];
    }
    v.values.resize(v.grid.voxels());
    // LayoutXYZ: x fastest, the Volume's order (VDB's own default, LayoutZYX, is z fastest).
    openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, v.values.data());
    openvdb::tools::copyToDense(*grid, dense);
    return v;
}

}  // namespace vr
