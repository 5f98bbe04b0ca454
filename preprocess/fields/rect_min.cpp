#include "preprocess/fields/rect_min.h"

#include "preprocess/fields/byte_rows.h"

namespace vr {

namespace {

// Number of levels for windows up to maxLen inside n voxels: 2^(levels-1) <= min(maxLen, n).
int levelCount(int maxLen, int n) { return std::bit_width(unsigned(std::clamp(maxLen, 1, n))); }

}  // namespace

uint8_t* RectMin::resize(int nu, int nw) {
    nu_ = nu;
    nw_ = nw;
    plane_ = std::size_t(nu) * nw;
    reserveLevels(1);
    return table_.data();
}

void RectMin::reserveLevels(int count) {
    if (table_.size() < std::size_t(count) * plane_) table_.resize(std::size_t(count) * plane_);
}

void RectMin::build(const Levels& levels) {
    int levelsU = 0, levelsW = 1;
    for (int i = 0; i < int(levels.size()); ++i)
        if (levels[i]) {
            levelsU = i + 1;
            levelsW = std::max(levelsW, int(std::bit_width(levels[i])));
        }
    squares_ = false;
    levelsW_ = levelsW;
    reserveLevels(std::max(levelsU, 1) * levelsW);
    // Level (i, 0) from (i-1, 0): two windows of 2^(i-1) along u.
    for (int i = 1; i < levelsU; ++i) {
        const int half = 1 << (i - 1), width = nu_ - (1 << i) + 1;
        const uint8_t* src = level(i - 1, 0);
        uint8_t* dst = level(i, 0);
        for (int w = 0; w < nw_; ++w) minOfRows(src + at(0, w), src + at(half, w), dst + at(0, w), width);
    }
    // Level (i, j) from (i, j-1): two windows of 2^(j-1) along w, up to the highest j asked for with this i.
    for (int i = 0; i < levelsU; ++i) {
        const int width = nu_ - (1 << i) + 1;
        for (int j = 1; j < int(std::bit_width(levels[i])); ++j) {
            const int half = 1 << (j - 1), height = nw_ - (1 << j) + 1;
            const uint8_t* src = level(i, j - 1);
            uint8_t* dst = level(i, j);
            for (int w = 0; w < height; ++w) minOfRows(src + at(0, w), src + at(0, w + half), dst + at(0, w), width);
        }
    }
}

void RectMin::buildSquares(int maxLen) {
    const int levels = std::min(levelCount(maxLen, nu_), levelCount(maxLen, nw_));
    squares_ = true;
    reserveLevels(levels);
    // Level (i, i) from (i-1, i-1): four windows of 2^(i-1).
    for (int i = 1; i < levels; ++i) {
        const int half = 1 << (i - 1), width = nu_ - (1 << i) + 1, height = nw_ - (1 << i) + 1;
        const uint8_t* src = level(i - 1, i - 1);
        uint8_t* dst = level(i, i);
        for (int w = 0; w < height; ++w)
            minOfRows(src + at(0, w), src + at(half, w), src + at(0, w + half), src + at(half, w + half),
                      dst + at(0, w), width);
    }
}

}  // namespace vr
