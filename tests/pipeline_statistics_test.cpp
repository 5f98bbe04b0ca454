// The statistics a prepared file stores (preprocess/pipeline/prepared_statistics.h): the mean leap of each field
// as its voxels' boxes decode, for every code the EACD may be stored in.
#include <gtest/gtest.h>

#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/prepared_statistics.h"

namespace vr {
namespace {

// Boxes of 23 x 6 x 3 voxels: extents beyond the values each code holds exactly (log16 above 16, joint8 above 2).
Regions boxRegions(const Vec3i& dims) {
    Regions r;
    r.dims = dims;
    r.label.resize(voxelCount(dims));
    const Vec3i boxes{(dims.x + 22) / 23, (dims.y + 5) / 6, (dims.z + 2) / 3};
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                r.label[(std::size_t(z) * dims.y + y) * dims.x + x] =
                    uint32_t((z / 3 * boxes.y + y / 6) * boxes.x + x / 23);
    r.count = uint32_t(boxes.x * boxes.y * boxes.z);
    return r;
}

TEST(PipelineStatistics, MeanExtentsAreTheMeansOfTheDecodedBoxesInEveryCode) {
    const Regions regions = boxRegions({70, 31, 17});
    for (ExtentCode code : {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8}) {
        SCOPED_TRACE(std::string(extentCodeName(code)));
        PreparedVolume p;
        p.scalars.grid.dims = regions.dims;
        p.regions = regions;
        p.fields = buildFields(regions, kFieldEACD, code, [](FieldKind) {});
        const nlohmann::json means = preparedStatistics(p, {})["leaps"]["eacdMeanExtent"];
        ASSERT_EQ(means.size(), std::size_t(kOctants));
        for (int o = 0; o < kOctants; ++o) {
            const ExtentField& f = p.fields.eacd[o];
            ASSERT_EQ(f.code(), code);
            double sum[3] = {0, 0, 0};
            for (std::size_t i = 0; i < f.size(); ++i)
                for (int a = 0; a < 3; ++a) sum[a] += f[i][a];
            for (int a = 0; a < 3; ++a)
                EXPECT_NEAR(means[o][a].get<double>(), sum[a] / double(f.size()), 1e-12) << "octant " << o;
        }
        // Some box is larger than a code's exact values: the decode is what is measured.
        EXPECT_GT(means[0][0].get<double>(), 3.0);
    }
}

}  // namespace
}  // namespace vr
