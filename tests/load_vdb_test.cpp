// OpenVDB files written with OpenVDB's io::File and io::Stream, read back densified over the active bounding box.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <cstdint>
#include <fstream>
#include <initializer_list>

#include "core/errors.h"
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

// A float grid whose leaves hold every kind of inactive values that io::writeCompressedValues tells apart (none
// but the background, minus the background, one or two other values, three or more), across two root children, with
// tiles at the root and in internal nodes: every compression and half floats must pass the loader's walk of the tree
// (preprocess/load/vdb/vdb_file_check.cpp) and load with the values OpenVDB holds.
openvdb::FloatGrid::Ptr everyKindOfNode() {
    auto grid = openvdb::FloatGrid::create(0.5f);
    grid->setName("density");
    auto acc = grid->getAccessor();
    // x crosses 4096 (a root child's extent), y and z cross 8 (a leaf's): 8 leaves in two root children.
    for (int z = 6; z <= 9; ++z)
        for (int y = 6; y <= 9; ++y)
            for (int x = 4090; x <= 4101; ++x) {
                const openvdb::Coord c(x, y, z);
                const int leaf = (x >= 4096) * 4 + (y >= 8) * 2 + (z >= 8);
                acc.setValue(c, float((x - 4090) + y * 16 + z * 64) * 0.25f);
                if ((x + y + z) % 3 != 0) continue;
                const float inactive[] = {0.5f, -0.5f, 3.0f, x % 2 ? 3.0f : 0.5f, x % 2 ? 3.0f : 4.0f,
                                          float(x % 5), 0.5f, -0.5f};
                acc.setValueOff(c, inactive[leaf]);
            }
    // Leaves whose every inactive voxel is minus the background, one other value, or one of two others.
    for (int leaf = 0; leaf < 3; ++leaf)
        for (int z = 0; z < 8; ++z)
            for (int y = 24 + 8 * leaf; y < 32 + 8 * leaf; ++y)
                for (int x = 4096; x < 4104; ++x)
                    if (x == 4096 && z == 0)
                        acc.setValue(openvdb::Coord(x, y, z), float(leaf));
                    else
                        acc.setValueOff(openvdb::Coord(x, y, z), leaf == 0 ? -0.5f : leaf == 1 || y % 2 ? 3.0f : 4.0f);
    grid->tree().addTile(1, openvdb::Coord(4096, 16, 0), 7.25f, true);      // an active 8^3 tile in the box
    grid->tree().addTile(1, openvdb::Coord(4096, 128, 0), 9.0f, false);     // an inactive one elsewhere
    grid->tree().addTile(3, openvdb::Coord(-8192, 0, 0), 2.0f, false);      // an inactive root tile
    return grid;
}

// The file at path loads as grid's values over its active bounding box.
void expectLoadedAs(const fs::path& path, const openvdb::FloatGrid& grid) {
    const Volume v = loadVolume(path);
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    ASSERT_EQ(v.grid.dims, Vec3i(box.dim().x(), box.dim().y(), box.dim().z()));
    for (int z = 0; z < v.grid.dims.z; ++z)
        for (int y = 0; y < v.grid.dims.y; ++y)
            for (int x = 0; x < v.grid.dims.x; ++x)
                ASSERT_EQ(v.at(x, y, z), grid.tree().getValue(box.min() + openvdb::Coord(x, y, z)))
                    << x << " " << y << " " << z;
}

TEST(LoadVdb, EveryCompressionAndHalfFloatsLoad) {
    openvdb::initialize();
    using namespace openvdb::io;
    for (const std::uint32_t compression : std::initializer_list<std::uint32_t>{
             COMPRESS_NONE, COMPRESS_ZIP, COMPRESS_ACTIVE_MASK, COMPRESS_ZIP | COMPRESS_ACTIVE_MASK, COMPRESS_BLOSC,
             COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK}) {
        for (const bool half : {false, true}) {
            SCOPED_TRACE(compressionToString(compression) + (half ? ", half floats" : ""));
            const openvdb::FloatGrid::Ptr grid = everyKindOfNode();
            grid->setSaveFloatAsHalf(half);  // every value above is a multiple of 1/4, exact in half floats
            const fs::path path = test::scratchDir("load_vdb_every") / "every.vdb";
            openvdb::io::File file(path.string());
            file.setCompression(compression);
            file.write({grid});
            file.close();

            expectLoadedAs(path, *grid);
        }
    }
}

// A float grid that shares another's tree is written as an instance (no tree of its own); the loader, reading the
// first name ("a"), gets its parent's tree.
TEST(LoadVdb, InstancedFloatGridLoadsItsParentsTree) {
    openvdb::initialize();
    const openvdb::FloatGrid::Ptr parent = everyKindOfNode();
    parent->setName("z");
    const openvdb::FloatGrid::Ptr instance = parent->copy();  // shares the tree
    instance->setName("a");
    const fs::path path = test::scratchDir("load_vdb_instance") / "instance.vdb";
    writeGrids(path, {parent, instance});
    expectLoadedAs(path, *parent);
}

// Memory follows the file: an active tile of 128^3 voxels (2 Mi) in a file of a few KiB loads, two voxels 600 apart
// on each axis (a box of 216 Mi voxels, beyond 16 Mi and 256 per byte of the file) are refused before densifying.
TEST(LoadVdb, DenseBoxBoundedByTheFile) {
    openvdb::initialize();
    const fs::path dir = test::scratchDir("load_vdb_sparse");
    auto tile = openvdb::FloatGrid::create(0.0f);
    tile->tree().addTile(2, openvdb::Coord(0, 0, 0), 1.5f, true);
    writeGrids(dir / "tile.vdb", {tile});
    const Volume v = loadVolume(dir / "tile.vdb");
    EXPECT_EQ(v.grid.dims, Vec3i(128, 128, 128));
    EXPECT_EQ(v.at(127, 0, 64), 1.5f);

    auto apart = openvdb::FloatGrid::create(0.0f);
    apart->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    apart->tree().setValue(openvdb::Coord(599, 599, 599), 2.0f);
    writeGrids(dir / "apart.vdb", {apart});
    try {
        loadVolume(dir / "apart.vdb");
        FAIL() << "densified 600^3 voxels from a file of " << fs::file_size(dir / "apart.vdb") << " bytes";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("apart.vdb"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("densifies to 216000000 voxels"), std::string::npos) << e.what();
    }
}

// A stream (io::Stream: no grid offsets), which io::File reads whole: its float trees are walked before, and a tree
// of another type, which the loader cannot check, is refused.
TEST(LoadVdb, StreamWithoutGridOffsets) {
    openvdb::initialize();
    const fs::path dir = test::scratchDir("load_vdb_stream");
    const openvdb::FloatGrid::Ptr grid = everyKindOfNode();
    {
        std::ofstream out(dir / "floats.vdb", std::ios::binary);
        openvdb::io::Stream(out).write({grid});
    }
    expectLoadedAs(dir / "floats.vdb", *grid);

    auto ints = openvdb::Int32Grid::create(0);
    ints->tree().setValue(openvdb::Coord(0, 0, 0), 7);
    {
        std::ofstream out(dir / "ints.vdb", std::ios::binary);
        openvdb::io::Stream(out).write({ints, grid});
    }
    try {
        loadVolume(dir / "ints.vdb");
        FAIL() << "loaded a stream holding an int32 tree";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("ints.vdb"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("Tree_int32_5_4_3"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vr
