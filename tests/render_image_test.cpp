// Image files: .exr keeps linear float RGBA exactly, .png holds the clamped sRGB picture; writes are atomic;
// unreadable files are refused by name.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>

#include "core/errors.h"
#include "io/crc32.h"
#include "support/datasets.h"
#include "render/image.h"
#include "render/png_file.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

Image gradientImage(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.pixel(x, y);
            p[0] = float(x) / (w - 1);
            p[1] = float(y) / (h - 1);
            p[2] = 0.25f + 1e-7f * float(x * y);
            p[3] = float(x + y) / (w + h - 2);
        }
    img.pixel(0, 0)[0] = -0.5f;  // out of range: clamped in 8-bit files, kept in float ones
    img.pixel(1, 0)[1] = 3.0f;
    return img;
}

std::string contents(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::size_t filesIn(const fs::path& dir) {
    return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(RenderImage, ExrRoundTripIsExact) {
    const fs::path dir = test::scratchDir("cpu_image_exr");
    const Image img = gradientImage(37, 23);
    writeImage(dir / "a.exr", img);
    const Image back = readImage(dir / "a.exr");
    ASSERT_EQ(back.width, 37);
    ASSERT_EQ(back.height, 23);
    EXPECT_EQ(maxAbsDifference(img, back), 0.0);
    EXPECT_EQ(filesIn(dir), 1u);  // no temporary left behind
}

// The code by search equals the code by the curve: on every 64th float in [0, 1], on the floats around each step, and
// on the values the clamp and NaN decide.
TEST(RenderImage, SrgbBytesBySearchAreTheCurves) {
    const uint32_t one = std::bit_cast<uint32_t>(1.0f);
    for (uint32_t bits = 0; bits <= one; bits += 64) {
        const float x = std::bit_cast<float>(bits);
        ASSERT_EQ(srgbByte(x), srgbByteByPower(x)) << x;
    }
    for (int k = 1; k <= 255; ++k) {  // the first float of each code, and its neighbours
        uint32_t bits = 0;
        while (srgbByte(std::bit_cast<float>(bits)) < k) bits += 1u << 12;
        for (uint32_t b = bits > (1u << 12) ? bits - (1u << 12) : 0; b <= bits; ++b)
            ASSERT_EQ(srgbByte(std::bit_cast<float>(b)), srgbByteByPower(std::bit_cast<float>(b))) << k;
    }
    for (float x : {-1.0f, -0.0f, 1e-40f, 1.0f, 1.5f, std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()})
        EXPECT_EQ(srgbByte(x), srgbByteByPower(x)) << x;
    EXPECT_EQ(srgbByte(0.5f), 188);
    EXPECT_EQ(srgbByte(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(RenderImage, PngIsClampedSrgbOverTheBackground) {
    const fs::path dir = test::scratchDir("cpu_image_png");
    const Image img = gradientImage(40, 30);
    writeImage(dir / "a.png", img);

    // The bytes: sRGB-encoded (linear 0.5 -> 188, linear 0.2159 -> 128), clamped, opaque.
    const PngPixels png = readPng(dir / "a.png");
    ASSERT_EQ(png.width, 40);
    ASSERT_EQ(png.height, 30);
    const std::vector<unsigned char> bytes = rgbOf(png);
    EXPECT_EQ(bytes, srgbBytes(img));
    EXPECT_EQ(bytes[0], 0);          // -0.5 clamped
    EXPECT_EQ(bytes[3 + 1], 255);    // 3.0 clamped
    EXPECT_EQ(bytes[39 * 3], 255);   // x = 1
    EXPECT_EQ(png.rgba[4 * 7 + 3], 255);
    Image probe(1, 1);
    probe.pixel(0, 0)[0] = 0.5f;
    probe.pixel(0, 0)[1] = 0.2159f;
    writeImage(dir / "probe.png", probe);
    EXPECT_EQ(rgbOf(readPng(dir / "probe.png")), (std::vector<unsigned char>{188, 128, 0}));

    // Reading decodes back to linear within the 8-bit quantisation; alpha reads as opaque.
    const Image back = readImage(dir / "a.png");
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x)
            for (int c = 0; c < 3; ++c) {
                const float want = std::clamp(img.pixel(x, y)[c], 0.f, 1.f);
                EXPECT_NEAR(back.pixel(x, y)[c], want, 0.005f) << x << " " << y << " " << c;
            }
    EXPECT_EQ(back.pixel(5, 5)[3], 1.f);
}

TEST(RenderImage, FailedWritesLeaveTheOldFileAndNoTemporary) {
    const fs::path dir = test::scratchDir("cpu_image_fail");
    const Image img = gradientImage(8, 8);
    // A folder that does not exist: InputError naming the path.
    try {
        writeImage(dir / "missing" / "a.png", img);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing/a.png"), std::string::npos) << e.what();
    }
    // A format not written here, over an existing file: the file stays as it was.
    const fs::path existing = dir / "keep.notaformat";
    std::ofstream(existing) << "old contents";
    EXPECT_THROW(writeImage(existing, img), InputError);
    EXPECT_EQ(contents(existing), "old contents");
    // A malformed image over an existing png.
    writeImage(dir / "a.png", img);
    const std::string before = contents(dir / "a.png");
    Image broken(4, 4);
    broken.rgba.resize(3);
    EXPECT_THROW(writeImage(dir / "a.png", broken), InputError);
    EXPECT_EQ(contents(dir / "a.png"), before);
    EXPECT_EQ(filesIn(dir), 2u);
    // Reading something that is not there.
    EXPECT_THROW(readImage(dir / "nothing.exr"), InputError);
}

// The PNG bytes go through a write and a read unchanged, at any size (rows of odd length included).
TEST(RenderImage, PngRoundTripKeepsTheBytes) {
    const fs::path dir = test::scratchDir("cpu_image_png_round_trip");
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{7, 3}, std::pair{300, 2}}) {
        std::vector<unsigned char> rgb(std::size_t(w) * h * 3);
        for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = (unsigned char)(i * 37 + i / 5);
        writePng(dir / "b.png", w, h, rgb);
        const PngPixels back = readPng(dir / "b.png");
        EXPECT_EQ(back.width, w);
        EXPECT_EQ(back.height, h);
        EXPECT_EQ(rgbOf(back), rgb) << w << "x" << h;
    }
    EXPECT_EQ(filesIn(dir), 1u);
}

// An unwritable place, and files that are not PNGs or are cut short: InputError naming the file, nothing written.
TEST(RenderImage, BadPngFilesAreRefusedByName) {
    const fs::path dir = test::scratchDir("cpu_image_png_bad");
    const std::vector<unsigned char> rgb(4 * 4 * 3, 200);
    auto expectRefused = [](const std::function<void()>& act, const std::string& name, const std::string& why) {
        try {
            act();
            ADD_FAILURE() << "no error for " << name;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    };
    // A folder where the file should be, and a folder that does not exist.
    fs::create_directories(dir / "taken.png");
    expectRefused([&] { writePng(dir / "taken.png", 4, 4, rgb); }, "taken.png", "");
    expectRefused([&] { writePng(dir / "missing" / "a.png", 4, 4, rgb); }, "missing/a.png", "");
    expectRefused([&] { writePng(dir / "short.png", 4, 4, std::vector<unsigned char>(5)); }, "short.png", "malformed");
    EXPECT_FALSE(fs::exists(dir / "short.png"));

    writePng(dir / "good.png", 4, 4, rgb);
    const std::string good = contents(dir / "good.png");
    // Cut in its header, and cut in its pixels.
    std::ofstream(dir / "cut.png", std::ios::binary) << good.substr(0, good.size() / 2);
    expectRefused([&] { readPng(dir / "cut.png"); }, "cut.png", "PNG");
    expectRefused([&] { readImage(dir / "cut.png"); }, "cut.png", "PNG");
    std::ofstream(dir / "tail.png", std::ios::binary) << good.substr(0, good.size() - 20);
    expectRefused([&] { readPng(dir / "tail.png"); }, "tail.png", "corrupt PNG");
    std::string garbled = good;
    for (std::size_t i = 40; i < garbled.size() - 12; ++i) garbled[i] = char(garbled[i] ^ 0x5a);  // past the header
    std::ofstream(dir / "garbled.png", std::ios::binary) << garbled;
    expectRefused([&] { readPng(dir / "garbled.png"); }, "garbled.png", "PNG");
    // A valid header claiming 20000 x 20000 pixels: refused before they are allocated.
    std::string huge = good;
    for (int i = 0; i < 2; ++i) {
        const std::uint32_t side = 20000;
        for (int b = 0; b < 4; ++b) huge[16 + 4 * i + b] = char(side >> (24 - 8 * b));
    }
    const std::uint32_t crc = crc32Of(huge.data() + 12, 17);  // IHDR's type and data
    for (int b = 0; b < 4; ++b) huge[29 + b] = char(crc >> (24 - 8 * b));
    std::ofstream(dir / "huge.png", std::ios::binary) << huge;
    expectRefused([&] { readPng(dir / "huge.png"); }, "huge.png", "20000x20000");
    std::ofstream(dir / "text.png") << "not a picture";
    expectRefused([&] { readPng(dir / "text.png"); }, "text.png", "not a readable PNG");
    expectRefused([&] { readPng(dir / "absent.png"); }, "absent.png", "cannot open");
    expectRefused([&] { readImage(dir / "picture.jpg"); }, "picture.jpg", ".png, .exr");
    // The same for a cut EXR.
    writeImage(dir / "good.exr", gradientImage(16, 16));
    const std::string exr = contents(dir / "good.exr");
    std::ofstream(dir / "cut.exr", std::ios::binary) << exr.substr(0, exr.size() / 2);
    expectRefused([&] { readImage(dir / "cut.exr"); }, "cut.exr", "EXR");
}

TEST(RenderImage, MaxAbsDifference) {
    Image a(3, 2), b(3, 2);
    EXPECT_EQ(maxAbsDifference(a, b), 0.0);
    b.pixel(2, 1)[3] = -0.25f;
    a.pixel(0, 0)[1] = 0.125f;
    EXPECT_EQ(maxAbsDifference(a, b), 0.25);
    a.pixel(1, 1)[0] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(maxAbsDifference(a, b), std::numeric_limits<double>::infinity());
    EXPECT_THROW(maxAbsDifference(a, Image(2, 3)), InputError);
}

}  // namespace
}  // namespace vr
