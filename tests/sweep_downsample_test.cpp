// volsweep --downsample: the box average the report sweeps its largest volumes with.
#include <gtest/gtest.h>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "sweep/downsample.h"

namespace vr {
namespace {

TEST(SweepDownsample, AveragesBlocksAndKeepsTheExtent) {
    Volume v = rampPhantom({5, 4, 3}, 0, 0, 4, {0.5, 1, 2});  // x = 0..4 along x
    v.grid.origin = {1, 2, 3};
    const Volume d = downsample(v, 2);
    EXPECT_EQ(d.grid.dims, (Vec3i{3, 2, 2}));
    EXPECT_EQ(d.grid.spacing, (Vec3d{1, 2, 4}));
    EXPECT_EQ(d.grid.origin, v.grid.origin);
    EXPECT_EQ(d.sourceType, v.sourceType);
    // Blocks average x in {0,1}, {2,3} and the partial {4}; every y and z alike.
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y) {
            EXPECT_FLOAT_EQ(d.at(0, y, z), 0.5f);
            EXPECT_FLOAT_EQ(d.at(1, y, z), 2.5f);
            EXPECT_FLOAT_EQ(d.at(2, y, z), 4.0f);
        }
}

TEST(SweepDownsample, RoundsIntegerVolumesAndKeepsFactorOne) {
    Volume v = checkerboardPhantom({4, 4, 4}, 0, 255);
    v.sourceType = ScalarType::UInt8;
    const Volume d = downsample(v, 2);  // four 0s and four 255s per block: 127.5 rounds to 128
    for (float x : d.values) EXPECT_EQ(x, 128.0f);
    EXPECT_EQ(downsample(v, 1).values, v.values);
    EXPECT_THROW(downsample(v, 0), InputError);
}

}  // namespace
}  // namespace vr
