// The face-minimum tables of the EACD walk (preprocess/fields/rect_min.h): every rectangle a build covers gives
// the brute-force minimum, on random images of several shapes, for both strip orientations and for squares.
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

TEST(FieldsRectMin, StripsBuiltForShorterRectanglesOnlyGiveThose) {
    // Tables along u up to 6 (for rectangles no taller than wide) and along w up to 3 (for taller ones): a later
    // build with fewer levels must not read levels of an earlier, larger one.
    std::mt19937 rng(6);
    const Image image = randomImage(33, 20, rng);
    RectMin table = tableOf(image);
    table.buildStrips(33, 20);
    std::copy(image.bytes.begin(), image.bytes.end(), table.resize(image.nu, image.nw));
    table.buildStrips(6, 3);
    const RectMin::Query query = table.query();
    for (int w0 = 0; w0 < image.nw; ++w0)
        for (int u0 = 0; u0 < image.nu; ++u0)
            for (int lw = 1; w0 + lw <= image.nw && lw <= 6; ++lw)
                for (int lu = 1; u0 + lu <= image.nu && lu <= 6; ++lu) {
                    if (lw <= lu ? lu > 6 : lw > 3) continue;
                    ASSERT_EQ(query(u0, w0, lu, lw), image.minOver(u0, w0, lu, lw));
                }
}

TEST(FieldsRectMin, SquaresUpToTheLargestBuilt) {
    std::mt19937 rng(7);
    for (const auto& [nu, nw] : kShapes) {
        const Image image = randomImage(nu, nw, rng);
        RectMin table = tableOf(image);
        const int largest = std::min(nu, nw);
        table.buildSquares(largest);
        const RectMin::Query query = table.query();
        for (int w0 = 0; w0 < nw; ++w0)
            for (int u0 = 0; u0 < nu; ++u0)
                for (int k = 1; u0 + k <= nu && w0 + k <= nw; ++k)
                    ASSERT_EQ(query(u0, w0, k, k), image.minOver(u0, w0, k, k));
    }
}

}  // namespace
}  // namespace vr
