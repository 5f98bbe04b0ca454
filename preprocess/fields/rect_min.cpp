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

void RectMin::buildStrips(int maxLenU, int maxLenW) {
    const int levelsU = levelCount(maxLenU, nu_), levelsW = levelCount(maxLenW, nw_);
    squares_ = false;
    levelsU_ = levelsU;
    levelsW_ = levelsW;
    reserveLevels(levelsU + levelsW - 1);
    // Level i along u from i - 1: two strips of 2^(i-1).
    for (int i = 1; i < levelsU; ++i) {
        const int half = 1 << (i - 1), width = nu_ - (1 << i) + 1;
        const uint8_t* src = level(i - 1);
        uint8_t* dst = level(i);
        for (int w = 0; w < nw_; ++w) minOfRows(src + at(0, w), src + at(half, w), dst + at(0, w), width);
    }
    // Level j along w from j - 1: whole rows, two strips of 2^(j-1).
    for (int j = 1; j < levelsW; ++j) {
        const int half = 1 << (j - 1), height = nw_ - (1 << j) + 1;
        const uint8_t* src = level(j == 1 ? 0 : levelsU + j - 2);
        uint8_t* dst = level(levelsU + j - 1);
        minOfRows(src, src + at(0, half), dst, height * nu_);
    }
}

void RectMin::buildSquares(int maxLen) {
    const int levels = std::min(levelCount(maxLen, nu_), levelCount(maxLen, nw_));
    squares_ = true;
    levelsU_ = levels;
    reserveLevels(levels);
    // Level (i, i) from (i-1, i-1): four windows of 2^(i-1).
    for (int i = 1; i < levels; ++i) {
        const int half = 1 << (i - 1), width = nu_ - (1 << i) + 1, height = nw_ - (1 << i) + 1;
        const uint8_t* src = level(i - 1);
        uint8_t* dst = level(i);
        for (int w = 0; w < height; ++w)
            minOfRows(src + at(0, w), src + at(half, w), src + at(0, w + half), src + at(half, w + half),
                      dst + at(0, w), width);
    }
}

}  // namespace vr
