// A GIF frame's own palette of at most 256 colours, chosen by median cut, and the frame's pixels as its indices.
#pragma once
#include <array>
#include <vector>

namespace vr {

struct PalettedFrame {
    std::vector<std::array<unsigned char, 3>> palette;  // at most `colours` distinct RGB entries
    std::vector<unsigned char> indices;                 // a pixel each, from the top row
};

// rgb: 3 bytes a pixel. A frame of at most `colours` distinct colours keeps them exactly.
PalettedFrame medianCut(const std::vector<unsigned char>& rgb, int colours = 256);

}  // namespace vr
