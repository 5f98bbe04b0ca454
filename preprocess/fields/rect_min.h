// Minimum of a 2D byte image over an axis-aligned rectangle: sparse tables of squares (O(1) a square) or of 1D
// strips (O(shorter side) a rectangle).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace vr {

class RectMin {
public:
    // The image to build from: nu x nw bytes, u fastest. Fill it, then call buildStrips() or buildSquares().
    uint8_t* resize(int nu, int nw);
    // Tables for any rectangle of lenU x lenW whose longer side is at most the longest asked for in its direction:
    // along u up to maxLenU (for lenW <= lenU), along w up to maxLenW (for lenW > lenU). 1D tables (strips of 2^i
    // along one axis) rather than all 2D levels: a query then walks its shorter side, which costs less than
    // building dozens of 2D levels for the few voxels of a slice that query.
    void buildStrips(int maxLenU, int maxLenW);
    // Tables for squares only, up to maxLen: a few levels instead of their square.
    void buildSquares(int maxLen);
    // Minimum over [u0, u0 + lenU) x [w0, w0 + lenW), inside the image, for a rectangle the last build made tables
    // for. A plain value, so that hot loops keep it in registers.
    class Query {
    public:
        uint8_t operator()(int u0, int w0, int lenU, int lenW) const {
            if (squares_) {  // four squares of 2^i in the corners
                const int i = std::bit_width(unsigned(lenU)) - 1;
                const uint8_t* t = table_ + std::size_t(i) * plane_;
                const std::size_t r0 = std::size_t(w0) * nu_ + u0, d = lenU - (1 << i);
                const std::size_t r1 = r0 + d * nu_;
                return std::min(std::min(t[r0], t[r0 + d]), std::min(t[r1], t[r1 + d]));
            }
            uint8_t m = 255;
            if (lenW <= lenU) {  // each row of the rectangle: two strips of 2^i along u
                const int i = std::bit_width(unsigned(lenU)) - 1;
                const uint8_t* t = table_ + std::size_t(i) * plane_ + std::size_t(w0) * nu_ + u0;
                const std::size_t du = lenU - (1 << i);
                for (int w = 0; w < lenW; ++w, t += nu_) m = std::min(m, std::min(t[0], t[du]));
                return m;
            }
            // Each column: two strips of 2^j along w.
            const int j = std::bit_width(unsigned(lenW)) - 1;
            const uint8_t* t = table_ + std::size_t(j ? levelsU_ + j - 1 : 0) * plane_ + std::size_t(w0) * nu_ + u0;
            const uint8_t* t1 = t + std::size_t(lenW - (1 << j)) * nu_;
            for (int u = 0; u < lenU; ++u) m = std::min(m, std::min(t[u], t1[u]));
            return m;
        }

    private:
        friend class RectMin;
        const uint8_t* table_;
        std::size_t nu_, plane_;
        int levelsU_;
        bool squares_;
    };
    Query query() const {
        Query q;
        q.table_ = table_.data();
        q.nu_ = std::size_t(nu_);
        q.plane_ = plane_;
        q.levelsU_ = levelsU_;
        q.squares_ = squares_;
        return q;
    }

private:
    std::size_t at(int u, int w) const { return std::size_t(w) * nu_ + u; }
    // Strip tables: level i (i < levelsU_) holds, at (u, w), the minimum over [u, u + 2^i) x {w} where that lies
    // inside; level levelsU_ + j - 1 (j >= 1) the minimum over {u} x [w, w + 2^j). Square tables: level i the
    // minimum over [u, u + 2^i) x [w, w + 2^i). Level 0 is the image.
    uint8_t* level(int index) { return table_.data() + std::size_t(index) * plane_; }
    void reserveLevels(int count);

    int nu_ = 0, nw_ = 0, levelsU_ = 1;
    bool squares_ = false;
    std::size_t plane_ = 0;
    std::vector<uint8_t> table_;  // level 0, the image, first
};

}  // namespace vr
