#include "sweep/strip_font.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <filesystem>
#include <system_error>

namespace vr {
namespace fs = std::filesystem;

namespace {
fs::path findFont(const char* file) {
    for (const char* folder : {"/usr/share/fonts", "/usr/local/share/fonts"}) {
        std::error_code error;
        for (fs::recursive_directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
            if (it->path().filename() == file) return it->path();
    }
    return {};
}
}  // namespace

StripFont::StripFont(int pixelSize) {
    const fs::path font = findFont("DejaVuSans.ttf");
    if (font.empty() || FT_Init_FreeType(&library_) != 0) return;
    if (FT_New_Face(library_, font.c_str(), 0, &face_) != 0 || FT_Set_Pixel_Sizes(face_, 0, FT_UInt(pixelSize)) != 0) {
        if (face_) FT_Done_Face(face_);
        face_ = nullptr;
    }
}

StripFont::~StripFont() {
    if (face_) FT_Done_Face(face_);
    if (library_) FT_Done_FreeType(library_);
}

void StripFont::draw(std::vector<unsigned char>& rgb, int width, int height, int x, int baseline,
                     const std::string& text) const {
    if (!face_) return;
    int pen = x;
    for (unsigned char ch : text) {
        if (FT_Load_Char(face_, ch, FT_LOAD_RENDER) != 0) continue;
        const FT_GlyphSlot glyph = face_->glyph;
        const FT_Bitmap& bitmap = glyph->bitmap;
        for (int row = 0; row < int(bitmap.rows); ++row)
            for (int col = 0; col < int(bitmap.width); ++col) {
                const int px = pen + glyph->bitmap_left + col, py = baseline - glyph->bitmap_top + row;
                if (px < 0 || py < 0 || px >= width || py >= height) continue;
                const int coverage = bitmap.buffer[row * bitmap.pitch + col];
                for (int c = 0; c < 3; ++c) {
                    unsigned char& v = rgb[(std::size_t(py) * width + px) * 3 + c];
                    v = (unsigned char)((v * (255 - coverage) + 255 * coverage + 127) / 255);
                }
            }
        pen += int(glyph->advance.x >> 6);
    }
}

}  // namespace vr
