// A float RGBA image (linear, premultiplied over the background) and its image files (PNG, OpenEXR).
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace vr {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgba;  // row-major from the top, 4 floats per pixel

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0.f) {}
    float* pixel(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
    const float* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

// Image files claiming more pixels (16384 x 16384) are refused as malformed before their pixels are allocated.
constexpr std::int64_t kMaxImageFilePixels = std::int64_t(16384) * 16384;

// The picture as seen, 3 bytes a pixel from the top row: RGB over the background, sRGB-encoded, clamped. What 8-bit
// image files and movie frames hold.
std::vector<unsigned char> srgbBytes(const Image& image);

// A linear channel's 8-bit sRGB code, clamped to [0, 1] (NaN: 0): srgbByteByPower's, found among the 255 values where
// the code steps up (8 comparisons), not by a power per channel (0.1 s for a 2048 x 2048 frame on one core).
unsigned char srgbByte(float linear);
// The same by the sRGB curve itself: round(255 x encode(linear)).
unsigned char srgbByteByPower(float linear);

// The image file formats, by extension in any case: .png (8-bit, sRGB-encoded RGB), .exr (linear float RGBA).
bool isImageFormat(const std::filesystem::path& path);

// Format by extension (isImageFormat); any other is refused. Written atomically; throws InputError naming the path.
void writeImage(const std::filesystem::path& path, const Image& image);
Image readImage(const std::filesystem::path& path);

// Max over pixels and channels of |a - b|.
double maxAbsDifference(const Image& a, const Image& b);

}  // namespace vr
