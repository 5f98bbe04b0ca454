// The image strip of a dataset: chosen settings' view-0 images above their error maps (|diff| x10).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vr {

struct StripColumn {
    std::string label, subLabel;       // two lines drawn above the column when a font is found
    std::filesystem::path image;       // PNG
    std::filesystem::path errorMap;    // PNG; empty: a black tile (the reference)
};

// Pastes the columns side by side, images on the top row, error maps below, labels above (StripFont), and writes
// the strip as a PNG. Throws InputError naming a tile that cannot be read or the output that cannot be written.
void writeImageStrip(const std::vector<StripColumn>& columns, const std::filesystem::path& output);

}  // namespace vr
