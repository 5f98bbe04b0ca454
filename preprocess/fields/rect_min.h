// Minimum of a 2D byte image over any axis-aligned rectangle in O(1): a 2D sparse table.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace vr {

class RectMin {
public:
    // The image to build from: nu x nw bytes, u fastest. Fill it, then call build() or buildSquares().
    uint8_t* resize(int nu, int nw);
    // Tables for every rectangle up to maxLenU x maxLenW (only the levels those need are built).
    void build(int maxLenU, int maxLenW);
    // Tables for squares only, up to maxLen: a few levels instead of their square.
    void buildSquares(int maxLen);
    // Minimum over [u0, u0 + lenU) x [w0, w0 + lenW): inside the image, 1 <= lenU <= maxLenU, 1 <= lenW <= maxLenW
    // of the last build (lenU == lenW after buildSquares). A plain value, so that hot loops keep it in registers.
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
