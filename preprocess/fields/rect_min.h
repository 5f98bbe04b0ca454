// Minimum of a 2D byte image over an axis-aligned rectangle: sparse tables of squares (O(1) a square) or of 1D
// strips (O(shorter side) a rectangle), as many levels as the queries are worth (LevelPlan).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace vr {

// Which strips (or squares) of 2^c are worth tabulating for the queries of one image: each level costs a pass over
// the image, and a query longer than the tabulated strips reads ceil(length / 2^c) of them per row (squares: that
// number squared) instead of 2 (4). Mostly a few long faces ask for the top levels of a slice.
class LevelPlan {
public:
    explicit LevelPlan(bool squares) : squares_(squares) {}
    // A query `length` long along the strips, `rows` rows (squares: rows == length).
    void add(int length, int rows) {
        const int top = std::bit_width(unsigned(length)) - 1;
        for (int c = 0; c <= top; ++c) {
            const long n = ((length - 1) >> c) + 1;
            reads_[c] += squares_ ? n * n : n * rows;
        }
        const long atTop = squares_ ? 4 : 2 * rows;  // the reads at its own level, and at any above
        done_[top + 1] += atTop;
        longest_ = std::max(longest_, length);
    }
    // The longest strip to tabulate (0 for no query) for an image of `pixels`.
    int longest(std::size_t pixels) const {
        if (longest_ == 0) return 0;
        // A level pass takes about as long as pixels / 8 scattered reads (16 bytes at a time; squares: 3 minima).
        const long pass = long(pixels) / 8 * (squares_ ? 3 : 1);
        const int top = std::bit_width(unsigned(longest_)) - 1;
        long best = -1, done = 0;
        int bestC = 0;
        for (int c = 0; c <= top; ++c) {
            done += done_[c];
            const long cost = c * pass + reads_[c] + done;
            if (best < 0 || cost < best) best = cost, bestC = c;
        }
        return 1 << bestC;
    }

private:
    bool squares_;
    int longest_ = 0;
    std::array<long, 9> reads_{};  // reads of the queries that need strips of 2^c or longer, with strips of 2^c
    std::array<long, 10> done_{};  // reads of those that need strips shorter than 2^c (their own level's)
};

class RectMin {
public:
    // The image to build from: nu x nw bytes, u fastest. Fill it, then call buildStrips() or buildSquares().
    uint8_t* resize(int nu, int nw);
    // Tables of strips along u up to maxLenU long and along w up to maxLenW (1D tables: strips of 2^i along one
    // axis, rather than all 2D levels: a query then walks its shorter side, which costs less than building dozens
    // of 2D levels for the few voxels of a slice that query). Any rectangle is answered, along its longer side (u
    // for lenW <= lenU): by two strips a row where they are tabulated that long, by more where not.
    void buildStrips(int maxLenU, int maxLenW);
    // Tables for squares up to maxLen (a few levels instead of their square); longer squares take more of them.
    void buildSquares(int maxLen);
    // Minimum over [u0, u0 + lenU) x [w0, w0 + lenW), inside the image, for the rectangles (or squares) of the
    // last build. A plain value, so that hot loops keep it in registers.
    class Query {
    public:
        uint8_t operator()(int u0, int w0, int lenU, int lenW) const {
            uint8_t m = 255;
            if (squares_) {  // squares of 2^i over the corners (four, where tabulated that long)
                const int i = levelFor(lenU, levelsU_), s = 1 << i;
                const uint8_t* t = table_ + std::size_t(i) * plane_ + std::size_t(w0) * nu_ + u0;
                cover(lenU, s, [&](int dw) { cover(lenU, s, [&](int du) { m = std::min(m, t[dw * nu_ + du]); }); });
                return m;
            }
            if (lenW <= lenU) {  // each row of the rectangle: strips of 2^i along u
                const int i = levelFor(lenU, levelsU_), s = 1 << i;
                const uint8_t* t = table_ + std::size_t(i) * plane_ + std::size_t(w0) * nu_ + u0;
                for (int w = 0; w < lenW; ++w, t += nu_) cover(lenU, s, [&](int du) { m = std::min(m, t[du]); });
                return m;
            }
            // Each column: strips of 2^j along w.
            const int j = levelFor(lenW, levelsW_), s = 1 << j;
            const uint8_t* t = table_ + std::size_t(j ? levelsU_ + j - 1 : 0) * plane_ + std::size_t(w0) * nu_ + u0;
            cover(lenW, s, [&](int dw) {
                const uint8_t* row = t + dw * nu_;
                for (int u = 0; u < lenU; ++u) m = std::min(m, row[u]);
            });
            return m;
        }

    private:
        friend class RectMin;
        // The level of the strips a length reads: the longest not longer than it, of those tabulated.
        static int levelFor(int len, int levels) { return std::min(int(std::bit_width(unsigned(len))), levels) - 1; }
        // f(d) for the starts of strips of s (<= len) covering [0, len): 0, s, 2s, ... and the last, len - s.
        template <typename F>
        static void cover(int len, int s, F f) {
            const int last = len - s;
            for (int d = 0; d < last; d += s) f(d);
            f(last);
        }

        const uint8_t* table_;
        std::size_t nu_, plane_;
        int levelsU_, levelsW_;
        bool squares_;
    };
    Query query() const {
        Query q;
        q.table_ = table_.data();
        q.nu_ = std::size_t(nu_);
        q.plane_ = plane_;
        q.levelsU_ = levelsU_;
        q.levelsW_ = levelsW_;
        q.squares_ = squares_;
        return q;
    }

private:
    std::size_t at(int u, int w) const { return std::size_t(w) * nu_ + u; }
    // Strip tables: level i (i < levelsU_) holds, at (u, w), the minimum over [u, u + 2^i) x {w} where that lies
    // inside; level levelsU_ + j - 1 (1 <= j < levelsW_) the minimum over {u} x [w, w + 2^j). Square tables
    // (levelsU_ of them): level i the minimum over [u, u + 2^i) x [w, w + 2^i). Level 0 is the image.
    uint8_t* level(int index) { return table_.data() + std::size_t(index) * plane_; }
    void reserveLevels(int count);

    int nu_ = 0, nw_ = 0, levelsU_ = 1, levelsW_ = 1;
    bool squares_ = false;
    std::size_t plane_ = 0;
    std::vector<uint8_t> table_;  // level 0, the image, first
};

}  // namespace vr
