// libpng's simplified API (png_image) reports errors in the image's message instead of longjmp, so that no C++
// frame is skipped on a malformed file.
#include "render/png_file.h"

#include <png.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "core/errors.h"
#include "io/atomic_file.h"
#include "render/image.h"

namespace vr {
namespace fs = std::filesystem;

namespace {
struct PngImageFree {
    void operator()(png_image* image) const { png_image_free(image); }
};

png_image emptyImage() {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    return image;
}
}  // namespace

void writePng(const fs::path& path, int width, int height, const std::vector<unsigned char>& rgb) {
    if (width <= 0 || height <= 0 || rgb.size() != std::size_t(width) * height * 3)
        throw fileError(path.string(), "cannot write an empty or malformed image");
    png_image image = emptyImage();
    image.width = png_uint_32(width);
    image.height = png_uint_32(height);
    image.format = PNG_FORMAT_RGB;  // 8-bit, not linear: written with an sRGB chunk
    // libpng's fast filters and zlib level: a 512 x 512 render is encoded in 4 ms instead of 19 (the last step of
    // every render, on one core), for a file 27-54 % larger (66 -> 84 KB, 77 -> 119 KB).
    image.flags |= PNG_IMAGE_FLAG_FAST;
    // Room for the largest PNG the image can make, so that it is compressed once (asking for the size first
    // compresses it twice).
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(image);
    std::vector<char> encoded(size);
    if (!png_image_write_to_memory(&image, encoded.data(), &size, 0, rgb.data(), 0, nullptr))
        throw fileError(path.string(), std::string("cannot encode PNG: ") + image.message);
    writeFileAtomically(path, [&](std::ostream& out) { out.write(encoded.data(), std::streamsize(size)); });
}

PngPixels readPng(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path.string(), "cannot open PNG for reading");
    const std::string bytes{std::istreambuf_iterator<char>(in), {}};
    if (in.bad()) throw fileError(path.string(), "cannot read PNG");

    png_image image = emptyImage();
    const std::unique_ptr<png_image, PngImageFree> release(&image);
    if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
        throw fileError(path.string(), std::string("not a readable PNG: ") + image.message);
    if (std::int64_t(image.width) * image.height > kMaxImageFilePixels)
        throw fileError(path.string(), "a PNG of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                           " pixels is more than an image file may hold here");
    image.format = PNG_FORMAT_RGBA;
    PngPixels pixels{int(image.width), int(image.height), std::vector<unsigned char>(PNG_IMAGE_SIZE(image))};
    if (!png_image_finish_read(&image, nullptr, pixels.rgba.data(), 0, nullptr))
        throw fileError(path.string(), std::string("corrupt PNG: ") + image.message);
    return pixels;
}

std::vector<unsigned char> rgbOf(const PngPixels& pixels) {
    std::vector<unsigned char> rgb(pixels.rgba.size() / 4 * 3);
    for (std::size_t p = 0; p < rgb.size() / 3; ++p)
        for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = pixels.rgba[p * 4 + c];
    return rgb;
}

}  // namespace vr
