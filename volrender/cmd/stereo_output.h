// Where a frame's images go: one view's image (ViewOutput), or a stereo pair's two eyes, in two outputs
// (NAME_left.EXT and NAME_right.EXT) or composed into one (side by side, top and bottom, a red-cyan anaglyph).
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "volrender/cmd/view_output.h"

namespace vr {

enum class StereoLayout { Separate, SideBySide, TopBottom, Anaglyph };
StereoLayout parseStereoLayout(std::string_view name);  // InputError naming --stereo-layout

// The pair in one image: left beside right, left above right, or the left eye's red with the right eye's green
// and blue.
Image composePair(const Image& left, const Image& right, StereoLayout layout);

// NAME.EXT -> NAME_left.EXT.
std::string eyePath(const std::string& path, std::string_view eye);

// Every file that `views` frames written to `path` make, in the order they are written: NAME.EXT, NAME_007.EXT,
// NAME_left_007.EXT and NAME_right_007.EXT, or one movie.
std::vector<std::string> frameFiles(const std::string& path, int views, std::optional<StereoLayout> layout);

// The width and height of a frame as written: a pair side by side is twice as wide, top and bottom twice as high.
std::pair<int, int> frameSize(int width, int height, std::optional<StereoLayout> layout);

class FrameOutput {
public:
    // `movie`: the size of one eye's image, the frames and their rate; no layout: one image a frame.
    FrameOutput(const std::string& path, const MovieSpec& movie, std::optional<StereoLayout> layout);
    bool isMovie() const { return outputs_.front().isMovie(); }
    std::string name(int view) const;  // the file (or the files, joined by " + ") that hold it
    void add(int view, const std::vector<Image>& images);  // one image, or the left eye's and the right's
    void finish();

private:
    std::optional<StereoLayout> layout_;
    std::vector<ViewOutput> outputs_;  // one, or the left eye's and the right's
};

}  // namespace vr
