#include "sweep/image_strip.h"

#include <algorithm>
#include <cstring>

#include "core/errors.h"
#include "render/png_file.h"
#include "sweep/strip_font.h"

namespace vr {
namespace fs = std::filesystem;

namespace {
constexpr int kGap = 8, kLabelHeight = 40, kMinPitch = 150, kFontSize = 13;
constexpr unsigned char kBackground = 38;  // grey 0.15

struct Picture {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;  // 3 bytes a pixel from the top row
};

Picture readTile(const fs::path& path) {
    const PngPixels png = readPng(path);
    return {png.width, png.height, rgbOf(png)};
}

// Copies `tile` with its top left corner at (x, y); what falls outside `strip` is cut off.
void paste(Picture& strip, int x, int y, const Picture& tile) {
    const int w = std::min(tile.width, strip.width - x);
    for (int row = 0; row < tile.height && y + row < strip.height; ++row)
        if (w > 0)
            std::memcpy(&strip.rgb[(std::size_t(y + row) * strip.width + x) * 3],
                        &tile.rgb[std::size_t(row) * tile.width * 3], std::size_t(w) * 3);
}
}  // namespace

void writeImageStrip(const std::vector<StripColumn>& columns, const fs::path& output) {
    if (columns.empty()) throw InputError(output.string() + ": no columns for the image strip");
    const Picture first = readTile(columns.front().image);
    const int w = first.width, h = first.height;
    const int cols = int(columns.size());
    const int pitch = std::max(w, kMinPitch) + kGap;  // room for the labels beside small images
    Picture strip{kGap + cols * pitch, kLabelHeight + 2 * h + 3 * kGap, {}};
    strip.rgb.assign(std::size_t(strip.width) * strip.height * 3, kBackground);
    const Picture black{w, h, std::vector<unsigned char>(std::size_t(w) * h * 3, 0)};
    const StripFont font(kFontSize);  // without the font the report names the columns
    for (int c = 0; c < cols; ++c) {
        const int x = kGap + c * pitch;
        paste(strip, x, kLabelHeight + kGap, readTile(columns[c].image));
        const int errorRow = kLabelHeight + 2 * kGap + h;
        paste(strip, x, errorRow, columns[c].errorMap.empty() ? black : readTile(columns[c].errorMap));
        font.draw(strip.rgb, strip.width, strip.height, x, kLabelHeight / 2 - 4, columns[c].label);
        font.draw(strip.rgb, strip.width, strip.height, x, kLabelHeight - 4, columns[c].subLabel);
    }
    writePng(output, strip.width, strip.height, strip.rgb);
}

}  // namespace vr
