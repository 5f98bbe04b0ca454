// Image files by extension: 8-bit PNG holds the picture as seen (RGB over the background, sRGB-encoded, clamped);
// .exr holds the linear float RGBA the renderer produced.
#include "render/image.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/errors.h"
#include "core/lower_case.h"
#include "render/exr_file.h"
#include "render/png_file.h"

namespace vr {
namespace fs = std::filesystem;

// The sRGB transfer curve (IEC 61966-2-1).
static double srgbEncode(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}
static double srgbDecode(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

namespace {
enum class ImageFormat { Png, Exr, Other };

ImageFormat formatOf(const fs::path& path) {
    const std::string ext = lowerCase(path.extension().string());
    return ext == ".png" ? ImageFormat::Png : ext == ".exr" ? ImageFormat::Exr : ImageFormat::Other;
}

InputError unknownFormat(const fs::path& path) {
    return fileError(path.string(), "not an image format written or read here (.png, .exr)");
}
}  // namespace

bool isImageFormat(const fs::path& path) { return formatOf(path) != ImageFormat::Other; }

unsigned char srgbByteByPower(float linear) {
    if (!(linear > 0)) return 0;  // NaN too (lround of NaN is unspecified)
    return (unsigned char)std::lround(255 * srgbEncode(linear));
}

namespace {

// The smallest float at which srgbByteByPower reaches k, for k = 1 .. 255: found once, by bisection over the bit
// patterns of the floats in [0, 1], which order as their values.
const std::array<float, 255>& srgbSteps() {
    static const std::array<float, 255> steps = [] {
        std::array<float, 255> s{};
        const uint32_t one = std::bit_cast<uint32_t>(1.0f);
        for (int k = 1; k <= 255; ++k) {
            uint32_t lo = 0, hi = one;
            while (lo < hi) {
                const uint32_t mid = lo + (hi - lo) / 2;
                if (srgbByteByPower(std::bit_cast<float>(mid)) >= k) hi = mid;
                else lo = mid + 1;
            }
            s[std::size_t(k - 1)] = std::bit_cast<float>(lo);
        }
        return s;
    }();
    return steps;
}

}  // namespace

unsigned char srgbByte(float linear) {
    if (!(linear > 0)) return 0;
    const std::array<float, 255>& steps = srgbSteps();
    return (unsigned char)(std::upper_bound(steps.begin(), steps.end(), linear) - steps.begin());
}

std::vector<unsigned char> srgbBytes(const Image& image) {
    std::vector<unsigned char> bytes(std::size_t(image.width) * image.height * 3);
    tbb::parallel_for(0, image.height, [&](int y) {
        const std::size_t first = std::size_t(y) * image.width, last = first + image.width;
        for (std::size_t p = first; p < last; ++p)
            for (int c = 0; c < 3; ++c) bytes[p * 3 + c] = srgbByte(image.rgba[p * 4 + c]);
    });
    return bytes;
}

void writeImage(const fs::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw fileError(path.string(), "cannot write an empty or malformed image");
    switch (formatOf(path)) {
        case ImageFormat::Png: return writePng(path, image.width, image.height, srgbBytes(image));
        case ImageFormat::Exr: return writeExr(path, image);
        case ImageFormat::Other: throw unknownFormat(path);
    }
}

Image readImage(const fs::path& path) {
    switch (formatOf(path)) {
        case ImageFormat::Exr: return readExr(path);
        case ImageFormat::Other: throw unknownFormat(path);
        case ImageFormat::Png: break;
    }
    // PNG files are sRGB-encoded (as written above); alpha is straight.
    const PngPixels png = readPng(path);
    Image image(png.width, png.height);
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        image.rgba[i] = i % 4 == 3 ? png.rgba[i] / 255.f : float(srgbDecode(png.rgba[i] / 255.0));
    return image;
}

double maxAbsDifference(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw InputError("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                         " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
    double d = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
        const double e = std::abs(double(a.rgba[i]) - double(b.rgba[i]));
        if (std::isnan(e)) return std::numeric_limits<double>::infinity();  // a NaN must never pass a comparison
        d = std::max(d, e);
    }
    return d;
}

}  // namespace vr
