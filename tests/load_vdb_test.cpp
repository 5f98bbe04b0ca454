// OpenVDB files written with OpenVDB's own io::File, read back densified over the active bounding box.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "preprocess/load/load_volume.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

void writeGrids(const fs::path& path, const openvdb::GridPtrVec& grids) {
    openvdb::io::File file(path.string());
    file.write(grids);
    file.close();
}

TEST(LoadVdb, FirstFloatGridIsDensifiedOverItsActiveBox) {
    openvdb::initialize();
    // An int grid first: the loader skips to the first float grid.
    auto ints = openvdb::Int32Grid::create(0);
    ints->setName("labels");
    ints->tree().setValue(openvdb::Coord(0, 0, 0), 7);

    auto density = openvdb::FloatGrid::create(-1.0f);  // inactive voxels inside the box read as the background
    density->setName("density");
    density->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    const openvdb::Coord lo(-3, 10, 4), hi(1, 13, 6);  // a 5x4x3 box away from the index origin
    auto acc = density->getAccessor();
    for (int z = lo.z(); z <= hi.z(); ++z)
        for (int y = lo.y(); y <= hi.y(); ++y)
            for (int x = lo.x(); x <= hi.x(); ++x)
                if ((x + y + z) % 4 != 0) acc.setValue(openvdb::Coord(x, y, z), float(x * 100 + y * 10 + z) * 0.5f);
    acc.setValue(lo, 1.5f);
    acc.setValue(hi, 2.5f);

    const fs::path path = test::scratchDir("load_vdb") / "two_grids.vdb";
    writeGrids(path, {ints, density});
    const Volume v = loadVolume(path);

    ASSERT_EQ(v.grid.dims, Vec3i(5, 4, 3));
    EXPECT_EQ(v.sourceType, ScalarType::Float32);
    EXPECT_EQ(v.grid.spacing, Vec3d(0.25, 0.25, 0.25));
    // Voxel centres are at index * voxel size, so the corner of the box's first voxel is half a voxel before.
    EXPECT_DOUBLE_EQ(v.grid.origin.x, (-3 - 0.5) * 0.25);
    EXPECT_DOUBLE_EQ(v.grid.origin.y, (10 - 0.5) * 0.25);
    EXPECT_DOUBLE_EQ(v.grid.origin.z, (4 - 0.5) * 0.25);
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 5; ++x) {
                const openvdb::Coord c(lo.x() + x, lo.y() + y, lo.z() + z);
                ASSERT_EQ(v.at(x, y, z), density->tree().getValue(c)) << x << " " << y << " " << z;
            }
    EXPECT_EQ(v.at(0, 0, 0), 1.5f);
    EXPECT_EQ(v.at(4, 3, 2), 2.5f);
    EXPECT_EQ(v.at(1, 0, 0), -1.0f);  // (-2,10,4): inactive, the background
}

TEST(LoadVdb, AnisotropicVoxelSize) {
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    auto transform = openvdb::math::Transform::createLinearTransform(1.0);
    transform->preScale(openvdb::Vec3d(0.5, 2.0, 3.0));
    grid->setTransform(transform);
    grid->tree().setValue(openvdb::Coord(0, 0, 0), 4.0f);
    grid->tree().setValue(openvdb::Coord(1, 2, 3), 8.0f);
    const fs::path path = test::scratchDir("load_vdb_aniso") / "aniso.vdb";
    writeGrids(path, {grid});
    const Volume v = loadVolume(path);
    ASSERT_EQ(v.grid.dims, Vec3i(2, 3, 4));
    EXPECT_EQ(v.grid.spacing, Vec3d(0.5, 2.0, 3.0));
    EXPECT_EQ(v.at(0, 0, 0), 4.0f);
    EXPECT_EQ(v.at(1, 2, 3), 8.0f);
    EXPECT_EQ(v.at(1, 1, 1), 0.0f);
}

}  // namespace
}  // namespace vr
