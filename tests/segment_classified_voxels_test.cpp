#include "preprocess/segment/classified_voxels.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "preprocess/classify/classify.h"
#include "preprocess/segment/region_key.h"
#include "support/load_dataset.h"
#include "support/volumes.h"

namespace vr {
namespace {

Volume smoothFloatVolume(Vec3i dims) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> noise(-3, 3);
    return test::volumeOf(dims, {0.8, 1.1, 2}, ScalarType::Float32, [&](int x, int y, int z) {
        return 40 * std::sin(0.3 * x) + 25 * std::cos(0.2 * y + 0.4 * z) + noise(rng);
    });
}

// Segmentation reads the voxels classified on demand from the scalars and the table: each one exactly as classify()
// stores it, on an integer CT and on a float volume whose voxels fall between the table's entries.
TEST(SegmentClassifiedVoxels, OnDemandEqualTheClassifiedVolume) {
    const Volume ct = test::loadDataset("vtk_headsq_ct_64x64x93_uint16");
    const Volume smooth = smoothFloatVolume({23, 17, 11});
    for (const auto& [volume, tf] : {std::pair{&ct, test::datasetTransferFunction("vtk_headsq_ct.tf.json")},
                                     std::pair{&smooth, test::linearTransferFunction(-60, 60)}}) {
        ClassifyParams params;
        params.transferFunction = tf;
        const ScalarClassification table = scalarClassification(*volume, params);
        ClassifiedVolume stored;
        classify(*volume, table, true, stored);
        const ClassifiedVoxels onDemand(*volume, table, true);
        ASSERT_TRUE(onDemand.hasNormals());
        for (std::size_t i = 0; i < stored.sigma.size(); ++i) {
            const VoxelOptics o = onDemand.optics(i);
            ASSERT_EQ(o.sigma, stored.sigma[i]) << i;
            ASSERT_EQ(onDemand.sigma(i), stored.sigma[i]) << i;  // looked up alone
            ASSERT_EQ(o.colour, stored.colour[i]) << i;
            ASSERT_EQ(onDemand.normal(i), stored.normal[i]) << i;
            ASSERT_EQ(onDemand.opacity(o.sigma), stored.opacity(i)) << i;
        }
        // A row's normals at once, as segmentation's normal classes take them: each one bit for bit.
        const Vec3i d = volume->grid.dims;
        std::vector<std::array<float, 3>> row(std::size_t(d.x));
        for (std::size_t first = 0; first < stored.sigma.size(); first += row.size()) {
            onDemand.normals(first, d.x, row.data());
            for (std::size_t x = 0; x < row.size(); ++x) ASSERT_EQ(row[x], stored.normal[first + x]) << first + x;
        }
        // And the keys of any stretch of voxels, rows and all, as the voxel-by-voxel key.
        for (const SegmentationParams p :
             {SegmentationParams{0.02, 5, true, true}, SegmentationParams{0, 0, true, true}}) {
            const RegionKeyer keyer(onDemand, p);
            std::vector<RegionKey> keys(std::size_t(3 * d.x + 7));
            keyer.normalKeys(std::size_t(d.x) - 3, keys.size(), keys.data());
            for (std::size_t k = 0; k < keys.size(); ++k)
                ASSERT_EQ(keys[k], keyer.normalKey(std::size_t(d.x) - 3 + k)) << k;
        }
        EXPECT_FALSE(ClassifiedVoxels(*volume, table, false).hasNormals());
    }
}

TEST(SegmentClassifiedVoxels, InconsistentInputIsAnInputError) {
    const Volume v = smoothFloatVolume({4, 4, 4});
    ClassifyParams params;
    params.transferFunction = test::linearTransferFunction(-60, 60);
    const ScalarClassification table = scalarClassification(v, params);
    Volume shortVolume = v;
    shortVolume.values.pop_back();
    EXPECT_THROW(ClassifiedVoxels(shortVolume, table, true), InputError);
    ScalarClassification noTable = table;
    noTable.table.colour.pop_back();
    EXPECT_THROW(ClassifiedVoxels(v, noTable, true), InputError);
    ClassifiedVolume stored;
    classify(v, table, true, stored);
    stored.normal.pop_back();
    EXPECT_THROW(ClassifiedVoxels{stored}, InputError);
}

}  // namespace
}  // namespace vr
