// The face-minimum tables of the EACD walk (preprocess/fields/rect_min.h): every rectangle gives the brute-force
// minimum whatever levels a build made, on random images of several shapes, for both strip orientations and for
// squares; and the levels a LevelPlan asks for.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "preprocess/fields/rect_min.h"

namespace vr {
namespace {

struct Image {
    int nu, nw;
    std::vector<uint8_t> bytes;
    uint8_t minOver(int u0, int w0, int lenU, int lenW) const {
        uint8_t m = 255;
        for (int w = w0; w < w0 + lenW; ++w)
            for (int u = u0; u < u0 + lenU; ++u) m = std::min(m, bytes[std::size_t(w) * nu + u]);
        return m;
    }
};

// Few distinct values, so that minima tie and move as rectangles grow.
Image randomImage(int nu, int nw, std::mt19937& rng) {
    Image image{nu, nw, std::vector<uint8_t>(std::size_t(nu) * nw)};
    for (auto& b : image.bytes) b = uint8_t(1 + std::uniform_int_distribution<int>(0, 5)(rng) * 40);
    return image;
}

RectMin tableOf(const Image& image) {
    RectMin table;
    std::copy(image.bytes.begin(), image.bytes.end(), table.resize(image.nu, image.nw));
    return table;
}

const std::pair<int, int> kShapes[] = {{1, 1}, {1, 9}, {9, 1}, {5, 7}, {17, 3}, {33, 20}};

TEST(FieldsRectMin, StripsGiveEveryRectangleTheyCover) {
    std::mt19937 rng(5);
    for (const auto& [nu, nw] : kShapes) {
        const Image image = randomImage(nu, nw, rng);
        RectMin table = tableOf(image);
        table.buildStrips(nu, nw);  // every rectangle of the image
        const RectMin::Query query = table.query();
        for (int w0 = 0; w0 < nw; ++w0)
            for (int u0 = 0; u0 < nu; ++u0)
                for (int lw = 1; w0 + lw <= nw; ++lw)
                    for (int lu = 1; u0 + lu <= nu; ++lu)
                        ASSERT_EQ(query(u0, w0, lu, lw), image.minOver(u0, w0, lu, lw))
                            << nu << "x" << nw << " at (" << u0 << ", " << w0 << "), " << lu << "x" << lw;
    }
}

TEST(FieldsRectMin, ShorterStripsGiveEveryRectangleToo) {
    // Tables along u up to 6 and along w up to 3 (or 1 and 1, or 2 and 4): a rectangle longer than its strips takes
    // several of them, and a later build with fewer levels must not read levels of an earlier, larger one.
    std::mt19937 rng(6);
    const Image image = randomImage(33, 20, rng);
    RectMin table = tableOf(image);
    table.buildStrips(33, 20);
    for (const auto& [maxU, maxW] : {std::pair{6, 3}, std::pair{1, 1}, std::pair{2, 4}}) {
        std::copy(image.bytes.begin(), image.bytes.end(), table.resize(image.nu, image.nw));
        table.buildStrips(maxU, maxW);
        const RectMin::Query query = table.query();
        for (int w0 = 0; w0 < image.nw; ++w0)
            for (int u0 = 0; u0 < image.nu; ++u0)
                for (int lw = 1; w0 + lw <= image.nw; ++lw)
                    for (int lu = 1; u0 + lu <= image.nu; ++lu)
                        ASSERT_EQ(query(u0, w0, lu, lw), image.minOver(u0, w0, lu, lw))
                            << maxU << " x " << maxW << ": " << lu << "x" << lw << " at (" << u0 << ", " << w0 << ")";
    }
}

TEST(FieldsRectMin, SquaresUpToAnyLargestBuilt) {
    std::mt19937 rng(7);
    for (const auto& [nu, nw] : kShapes) {
        const Image image = randomImage(nu, nw, rng);
        RectMin table = tableOf(image);
        // Up to the largest square, and up to 1 and 3 (longer squares then take several).
        for (const int largest : {std::min(nu, nw), 1, 3}) {
            std::copy(image.bytes.begin(), image.bytes.end(), table.resize(nu, nw));
            table.buildSquares(largest);
            const RectMin::Query query = table.query();
            for (int w0 = 0; w0 < nw; ++w0)
                for (int u0 = 0; u0 < nu; ++u0)
                    for (int k = 1; u0 + k <= nu && w0 + k <= nw; ++k)
                        ASSERT_EQ(query(u0, w0, k, k), image.minOver(u0, w0, k, k)) << largest;
        }
    }
}

TEST(FieldsRectMin, LevelPlanBuildsWhatTheQueriesAreWorth) {
    constexpr std::size_t kPixels = 256 * 256;
    EXPECT_EQ(LevelPlan(false).longest(kPixels), 0);  // no query: no table
    // One long face reads a strip per voxel rather than build 7 levels for it; thousands of them pay for the levels.
    LevelPlan few(false), many(false), squares(true);
    few.add(200, 3);
    EXPECT_EQ(few.longest(kPixels), 1);
    for (int q = 0; q < 5000; ++q) many.add(200, 3);
    EXPECT_EQ(many.longest(kPixels), 128);
    // A 6 x 6 square costs 4 reads with tables up to 4, 9 with 2, 36 with none: 2 levels pay off only for many.
    squares.add(6, 6);
    EXPECT_EQ(squares.longest(kPixels), 1);
    for (int q = 0; q < 20000; ++q) squares.add(6, 6);
    EXPECT_EQ(squares.longest(kPixels), 4);
}

}  // namespace
}  // namespace vr
