// PNG files through libpng's simplified API: 8-bit sRGB-encoded pixels, the way the picture is seen.
#pragma once
#include <filesystem>
#include <vector>

namespace vr {

// Writes 3 bytes a pixel from the top row (sRGB-encoded RGB, tagged sRGB), atomically. Throws InputError naming
// the path.
void writePng(const std::filesystem::path& path, int width, int height, const std::vector<unsigned char>& rgb);

struct PngPixels {
    int width = 0, height = 0;
    std::vector<unsigned char> rgba;  // 4 bytes a pixel from the top row: sRGB-encoded colour, straight alpha
};

// Any PNG (grey, palette, 16-bit, with or without alpha) as 8-bit sRGB RGBA; alpha 255 where the file has none.
// Throws InputError naming the path when it cannot be read or is no valid PNG.
PngPixels readPng(const std::filesystem::path& path);

// The RGB bytes of RGBA pixels, alpha dropped.
std::vector<unsigned char> rgbOf(const PngPixels& pixels);

}  // namespace vr
