// Image files through OpenImageIO. 8-bit files hold the picture as seen (RGB over the background, sRGB-encoded,
// clamped); .exr holds the linear float RGBA the renderer produced.
#include "render/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "io/atomic_file.h"
#include "core/errors.h"

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

static bool isFloatFormat(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
}

std::vector<unsigned char> srgbBytes(const Image& image) {
    std::vector<unsigned char> bytes(std::size_t(image.width) * image.height * 3);
    for (std::size_t p = 0; p < bytes.size() / 3; ++p)
        for (int c = 0; c < 3; ++c)
            bytes[p * 3 + c] = (unsigned char)std::lround(255 * srgbEncode(image.rgba[p * 4 + c]));
    return bytes;
}

void writeImage(const fs::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw fileError(path.string(), "cannot write an empty or malformed image");
    writePathAtomically(path, [&](const fs::path& tmp) {
        auto out = OIIO::ImageOutput::create(tmp.string());
        if (!out) throw fileError(path.string(), "cannot write: " + OIIO::geterror());
        bool ok;
        if (isFloatFormat(path)) {
            OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
            ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.rgba.data());
        } else {
            OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
            spec.attribute("oiio:ColorSpace", "sRGB");
            ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, srgbBytes(image).data());
        }
        ok = out->close() && ok;
        if (!ok) throw fileError(path.string(), "cannot write: " + out->geterror());
    });
}

Image readImage(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw fileError(path.string(), "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const int nc = spec.nchannels;
    std::vector<float> raw(std::size_t(spec.width) * spec.height * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data()))
        throw fileError(path.string(), "cannot read image: " + in->geterror());
    // 8-bit files are sRGB-encoded (as written above); float files are linear.
    const bool encoded = spec.format.basetype == OIIO::TypeDesc::UINT8;
    auto colour = [&](float v) { return encoded ? float(srgbDecode(v)) : v; };

    Image image(spec.width, spec.height);
    for (std::size_t p = 0; p < std::size_t(spec.width) * spec.height; ++p) {
        const float* src = &raw[p * nc];
        float* dst = &image.rgba[p * 4];
        for (int c = 0; c < 3; ++c) dst[c] = colour(src[nc >= 3 ? c : 0]);
        dst[3] = nc == 2 ? src[1] : (nc >= 4 ? src[3] : 1.f);
    }
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
