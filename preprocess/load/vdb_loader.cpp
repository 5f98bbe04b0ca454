// OpenVDB (.vdb): the first FloatGrid of the file, densified over its active voxels' bounding box.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

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
