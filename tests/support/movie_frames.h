// Movies read back for tests: every frame of a GIF or an MP4 (FFmpeg's libavformat and libavcodec) as 8-bit sRGB
// RGB, and PNG images to compare them with.
#pragma once
#include <filesystem>
#include <vector>

namespace vr::test {

struct Frames {
    int width = 0, height = 0;
    double fps = 0;
    std::vector<std::vector<unsigned char>> rgb;  // a frame each, 3 bytes a pixel from the top row
};

Frames readMovieFrames(const std::filesystem::path& path);
// A PNG (e.g. one volrender wrote) as one frame.
Frames readImageBytes(const std::filesystem::path& path);

// |a - b| over the bytes of two frames of one size, in 8-bit levels: the mean, the largest, and the share of the
// bytes that differ by more than 16 levels.
struct FrameDifference {
    double mean = 0;
    int max = 0;
    double beyond16 = 0;
};
FrameDifference frameDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b);

}  // namespace vr::test
