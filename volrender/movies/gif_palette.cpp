// Heckbert's median cut: the frame's distinct colours, weighted by how many pixels have them, start as one box; the
// box with the widest range in one channel is split at its pixels' median in that channel until there are as many
// boxes as colours (or no box holds two colours). A box's colour is the mean of its pixels; each pixel gets its
// colour's box.
#include "volrender/movies/gif_palette.h"

#include <algorithm>
#include <cstdint>

namespace vr {
namespace {

struct Bin {
    std::uint32_t rgb;  // 0xRRGGBB
    std::uint32_t pixels;
    int channel(int c) const { return int(rgb >> (16 - 8 * c)) & 0xff; }
};

struct Box {
    std::size_t begin, end;  // bins
    int widest = 0, range = 0;
};

Box measured(const std::vector<Bin>& bins, std::size_t begin, std::size_t end) {
    Box box{begin, end};
    const auto first = bins.begin() + std::ptrdiff_t(begin), last = bins.begin() + std::ptrdiff_t(end);
    for (int c = 0; c < 3; ++c) {
        const auto [lo, hi] =
            std::minmax_element(first, last, [c](const Bin& a, const Bin& b) { return a.channel(c) < b.channel(c); });
        if (hi->channel(c) - lo->channel(c) > box.range) box = {begin, end, c, hi->channel(c) - lo->channel(c)};
    }
    return box;
}

// Sorts the box's bins along its widest channel and cuts where half its pixels lie below; both halves keep a bin.
std::pair<Box, Box> split(std::vector<Bin>& bins, const Box& box) {
    const auto first = bins.begin() + std::ptrdiff_t(box.begin), last = bins.begin() + std::ptrdiff_t(box.end);
    const int c = box.widest;
    std::sort(first, last, [c](const Bin& a, const Bin& b) { return a.channel(c) < b.channel(c); });
    std::uint64_t total = 0;
    for (auto b = first; b != last; ++b) total += b->pixels;
    std::uint64_t below = first->pixels;
    std::size_t cut = box.begin + 1;
    while (cut + 1 < box.end && 2 * (below + bins[cut].pixels) <= total) below += bins[cut++].pixels;
    return {measured(bins, box.begin, cut), measured(bins, cut, box.end)};
}

}  // namespace

PalettedFrame medianCut(const std::vector<unsigned char>& rgb, int colours) {
    const std::size_t n = rgb.size() / 3;
    std::vector<std::uint32_t> packed(n);
    for (std::size_t p = 0; p < n; ++p)
        packed[p] = std::uint32_t(rgb[3 * p]) << 16 | std::uint32_t(rgb[3 * p + 1]) << 8 | rgb[3 * p + 2];
    std::vector<std::uint32_t> distinct = packed;
    std::sort(distinct.begin(), distinct.end());
    std::vector<Bin> bins;
    for (std::uint32_t c : distinct)
        if (bins.empty() || bins.back().rgb != c)
            bins.push_back({c, 1});
        else
            ++bins.back().pixels;

    PalettedFrame frame;
    if (bins.empty()) return frame;
    std::vector<Box> boxes{measured(bins, 0, bins.size())};
    while (int(boxes.size()) < colours) {
        const auto widest = std::max_element(boxes.begin(), boxes.end(),
                                             [](const Box& a, const Box& b) { return a.range < b.range; });
        if (widest->range == 0) break;  // every box holds one colour
        const auto [low, high] = split(bins, *widest);
        *widest = low;
        boxes.push_back(high);
    }

    // Each box's mean colour, once in the palette (boxes of one mean share an entry: libavcodec's GIF encoder
    // mistakes the pixels of a repeated entry); each distinct colour its box's entry.
    std::vector<std::pair<std::uint32_t, unsigned char>> indexOf;
    for (const Box& box : boxes) {
        std::uint64_t sum[3] = {}, pixels = 0;
        for (std::size_t b = box.begin; b < box.end; ++b) {
            for (int c = 0; c < 3; ++c) sum[c] += std::uint64_t(bins[b].channel(c)) * bins[b].pixels;
            pixels += bins[b].pixels;
        }
        std::array<unsigned char, 3> mean;
        for (int c = 0; c < 3; ++c) mean[c] = (unsigned char)((sum[c] + pixels / 2) / pixels);
        const auto entry = std::find(frame.palette.begin(), frame.palette.end(), mean);
        const auto index = (unsigned char)(entry - frame.palette.begin());
        if (entry == frame.palette.end()) frame.palette.push_back(mean);
        for (std::size_t b = box.begin; b < box.end; ++b) indexOf.emplace_back(bins[b].rgb, index);
    }
    std::sort(indexOf.begin(), indexOf.end());
    frame.indices.resize(n);
    for (std::size_t p = 0; p < n; ++p)
        frame.indices[p] = std::lower_bound(indexOf.begin(), indexOf.end(), std::make_pair(packed[p], (unsigned char)0))
                               ->second;
    return frame;
}

}  // namespace vr
