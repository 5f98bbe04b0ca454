// The sweep report's image strip: the tiles pasted in their places (images above error maps, a black tile for a
// missing map) on a grey ground, written as a PNG; a tile that cannot be read is named and nothing is written.
#include <gtest/gtest.h>

#include <array>
#include <fstream>

#include "core/errors.h"
#include "render/png_file.h"
#include "support/datasets.h"
#include "sweep/image_strip.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

// A w x h tile of one colour.
fs::path tile(const fs::path& dir, const std::string& name, int w, int h, unsigned char r, unsigned char g,
              unsigned char b) {
    std::vector<unsigned char> rgb;
    for (int p = 0; p < w * h; ++p) rgb.insert(rgb.end(), {r, g, b});
    writePng(dir / name, w, h, rgb);
    return dir / name;
}

TEST(SweepImageStrip, TilesSitInTheirColumns) {
    const fs::path dir = test::scratchDir("sweep_image_strip");
    const std::vector<StripColumn> columns{
        {"", "", tile(dir, "ref.png", 20, 10, 200, 0, 0), {}},
        {"", "", tile(dir, "a.png", 20, 10, 0, 200, 0), tile(dir, "a_error.png", 20, 10, 0, 0, 200)}};
    writeImageStrip(columns, dir / "strip.png");
    const PngPixels strip = readPng(dir / "strip.png");
    // Columns 150 + 8 wide (room for the labels) after an 8-pixel margin; rows below 40 pixels of labels.
    ASSERT_EQ(strip.width, 8 + 2 * 158);
    ASSERT_EQ(strip.height, 40 + 2 * 10 + 3 * 8);
    auto at = [&](int x, int y) {
        const unsigned char* p = &strip.rgba[(std::size_t(y) * strip.width + x) * 4];
        return std::array<int, 3>{p[0], p[1], p[2]};
    };
    EXPECT_EQ(at(8, 48), (std::array<int, 3>{200, 0, 0}));
    EXPECT_EQ(at(27, 57), (std::array<int, 3>{200, 0, 0}));
    EXPECT_EQ(at(8, 66), (std::array<int, 3>{0, 0, 0}));  // the reference has no error map
    EXPECT_EQ(at(166, 48), (std::array<int, 3>{0, 200, 0}));
    EXPECT_EQ(at(185, 75), (std::array<int, 3>{0, 0, 200}));
    EXPECT_EQ(at(4, 4), (std::array<int, 3>{38, 38, 38}));  // the grey ground
    EXPECT_EQ(at(28, 48), (std::array<int, 3>{38, 38, 38}));
}

TEST(SweepImageStrip, AnUnreadableTileIsNamed) {
    const fs::path dir = test::scratchDir("sweep_image_strip_bad");
    std::ofstream(dir / "broken.png") << "not a picture";
    const std::vector<StripColumn> columns{{"", "", tile(dir, "ref.png", 4, 4, 1, 2, 3), {}},
                                           {"", "", tile(dir, "a.png", 4, 4, 1, 2, 3), dir / "broken.png"}};
    try {
        writeImageStrip(columns, dir / "strip.png");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "strip.png"));
}

}  // namespace
}  // namespace vr
