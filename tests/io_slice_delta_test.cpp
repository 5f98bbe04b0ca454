// The prepared file's slice differences within a block: decoding gives the block back, whatever the block's length
// against the slice's; the block's first slice is stored as it is, and slices that repeat become zeros.
#include "io/slice_delta.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace vr {
namespace {

TEST(IoSliceDelta, DecodesToTheBlock) {
    std::mt19937 rng(7);
    for (uint64_t slice : {1u, 3u, 16u, 40000u})
        for (uint64_t bytes : {0u, 1u, 2u, 15u, 16u, 17u, 100000u}) {
            SCOPED_TRACE("slice " + std::to_string(slice) + ", block " + std::to_string(bytes));
            std::vector<unsigned char> block(bytes), coded(bytes);
            for (unsigned char& c : block) c = static_cast<unsigned char>(rng());
            sliceDeltaEncode(block.data(), bytes, slice, coded.data());
            sliceDeltaDecode(coded.data(), bytes, slice);
            EXPECT_EQ(coded, block);
        }
}

TEST(IoSliceDelta, FirstSliceAsItIsAndRepeatedSlicesZero) {
    const std::vector<unsigned char> first = {200, 1, 255, 7};
    std::vector<unsigned char> block;
    for (int z = 0; z < 3; ++z) block.insert(block.end(), first.begin(), first.end());
    block[9] = 0;  // 1 -> 0 one slice on: -1 is 255 mod 256
    block.push_back(201);  // a slice cut short by the block's end
    std::vector<unsigned char> coded(block.size());
    sliceDeltaEncode(block.data(), block.size(), first.size(), coded.data());
    EXPECT_EQ(coded, (std::vector<unsigned char>{200, 1, 255, 7, 0, 0, 0, 0, 0, 255, 0, 0, 1}));
}

}  // namespace
}  // namespace vr
