// The order in which a dispatch's workgroup rows take the tile's rows on a CPU device (workgroup_rows.h).
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "volrender/vulkan/workgroup_rows.h"

namespace vr {
namespace {

// The tile rows that workgroup rows first .. first + count - 1 take.
std::vector<int> rowsTaken(int rows, int first, int count) {
    const int stride = interleavedRowStride(rows);
    std::vector<int> taken;
    for (int r = first; r < first + count; ++r) taken.push_back(int((long(r) * stride) % rows));
    return taken;
}

TEST(VulkanWorkgroupRows, EveryTileRowIsTakenOnce) {
    for (int rows = 1; rows <= 300; ++rows) {
        std::vector<int> seen(rows, 0);
        for (int row : rowsTaken(rows, 0, rows)) ++seen[row];
        for (int row = 0; row < rows; ++row) ASSERT_EQ(seen[row], 1) << rows << " rows, tile row " << row;
    }
}

// A thread's contiguous run of workgroup rows spreads over the whole tile: each half of the run (as llvmpipe's two
// threads take it) covers the tile's upper and lower halves alike, and so do four threads' quarters.
TEST(VulkanWorkgroupRows, ContiguousRunsSpreadOverTheTile) {
    for (int rows : {16, 64, 65, 128, 100, 127}) {
        for (int threads : {2, 4}) {
            const int run = rows / threads;
            for (int t = 0; t < threads; ++t) {
                int upper = 0;
                for (int row : rowsTaken(rows, t * run, run)) upper += row < rows / 2;
                EXPECT_NEAR(upper, run / 2.0, 2.0) << rows << " rows, thread " << t << " of " << threads;
            }
        }
    }
}

TEST(VulkanWorkgroupRows, FewRowsStayInOrder) {
    EXPECT_EQ(interleavedRowStride(1), 1);
    EXPECT_EQ(interleavedRowStride(2), 1);
    EXPECT_GT(interleavedRowStride(64), 1);
}

}  // namespace
}  // namespace vr
