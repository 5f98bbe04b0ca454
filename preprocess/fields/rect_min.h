// Minimum of a 2D byte image over any axis-aligned rectangle in O(1): a 2D sparse table.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace vr {

class RectMin {
public:
    // The image to build from: nu x nw bytes, u fastest. Fill it, then call build() or buildSquares().
    uint8_t* resize(int nu, int nw);
    // Level pairs (i, j) (a rectangle of lenU x lenW needs i = floor(log2 lenU), j = floor(log2 lenW)): bit j of
    // [i]. A rectangle query needs one pair, so only those asked for (and the chains to them) are built.
    using Levels = std::array<uint16_t, 16>;
    static void addLevels(Levels& levels, int lenU, int lenW) {
        levels[std::bit_width(unsigned(lenU)) - 1] |= uint16_t(1u << (std::bit_width(unsigned(lenW)) - 1));
    }
    // Tables for the rectangles of the level pairs in `levels`, all inside the image.
    void build(const Levels& levels);
    // Tables for squares only, up to maxLen: a few levels instead of their square.
    void buildSquares(int maxLen);
    // Minimum over [u0, u0 + lenU) x [w0, w0 + lenW), inside the image, for a rectangle the last build made tables
    // for (its level pair; after buildSquares, lenU == lenW <= maxLen). A plain value, so that hot loops keep it in
    // registers.
    class Query {
    public:
        uint8_t operator()(int u0, int w0, int lenU, int lenW) const {
            const int i = std::bit_width(unsigned(lenU)) - 1, j = std::bit_width(unsigned(lenW)) - 1;
            const uint8_t* t = table_ + std::size_t(squares_ ? i : i * levelsW_ + j) * plane_;
            const std::size_t r0 = std::size_t(w0) * nu_ + u0, du = lenU - (1 << i);
            const std::size_t r1 = std::size_t(w0 + lenW - (1 << j)) * nu_ + u0;
            return std::min(std::min(t[r0], t[r0 + du]), std::min(t[r1], t[r1 + du]));
        }

    private:
        friend class RectMin;
        const uint8_t* table_;
        std::size_t nu_, plane_;
        int levelsW_;
        bool squares_;
    };
    Query query() const {
        Query q;
        q.table_ = table_.data();
        q.nu_ = std::size_t(nu_);
        q.plane_ = plane_;
        q.levelsW_ = levelsW_;
        q.squares_ = squares_;
        return q;
    }

private:
    std::size_t at(int u, int w) const { return std::size_t(w) * nu_ + u; }
    // Level (i, j) holds, at (u, w), the minimum over [u, u + 2^i) x [w, w + 2^j) where that lies inside.
    // Square tables store level (i, i) at index i (as Query does).
    std::size_t levelOffset(int i, int j) const { return std::size_t(squares_ ? i : i * levelsW_ + j) * plane_; }
    const uint8_t* level(int i, int j) const { return table_.data() + levelOffset(i, j); }
    uint8_t* level(int i, int j) { return table_.data() + levelOffset(i, j); }
    void reserveLevels(int count);

    int nu_ = 0, nw_ = 0, levelsW_ = 1;
    bool squares_ = false;
    std::size_t plane_ = 0;
    std::vector<uint8_t> table_;  // level (0, 0), the image, first
};

}  // namespace vr
