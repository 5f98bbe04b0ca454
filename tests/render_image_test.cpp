// Image files: .exr keeps linear float RGBA exactly, .png holds the clamped sRGB picture; writes are atomic.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "core/errors.h"
#include "support/datasets.h"
#include "render/image.h"

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

TEST(RenderImage, PngIsClampedSrgbOverTheBackground) {
    const fs::path dir = test::scratchDir("cpu_image_png");
    const Image img = gradientImage(40, 30);
    writeImage(dir / "a.png", img);

    // The bytes: 3 channels, sRGB-encoded (linear 0.5 -> 188, linear 0.2159 -> 128), clamped.
    auto in = OIIO::ImageInput::open((dir / "a.png").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().nchannels, 3);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
    std::vector<unsigned char> bytes(40 * 30 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, bytes.data()));
    EXPECT_EQ(bytes[0], 0);          // -0.5 clamped
    EXPECT_EQ(bytes[3 + 1], 255);    // 3.0 clamped
    EXPECT_EQ(bytes[39 * 3], 255);   // x = 1
    Image probe(1, 1);
    probe.pixel(0, 0)[0] = 0.5f;
    probe.pixel(0, 0)[1] = 0.2159f;
    writeImage(dir / "probe.png", probe);
    auto pin = OIIO::ImageInput::open((dir / "probe.png").string());
    unsigned char rgb[3];
    ASSERT_TRUE(pin->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb));
    EXPECT_EQ(rgb[0], 188);
    EXPECT_EQ(rgb[1], 128);
    EXPECT_EQ(rgb[2], 0);

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
    // A format OpenImageIO cannot write, over an existing file: the file stays as it was.
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
