// Movies of an orbit's views: an animated GIF or an H.264 MP4 (both through FFmpeg's libavcodec and libavformat),
// frame by frame as they are rendered, under a temporary name until the last frame is in.
#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "render/image.h"

namespace vr {

enum class MovieFormat { Gif, Mp4 };

// By extension, any case: .gif, .mp4; nothing for any other.
std::optional<MovieFormat> movieFormat(const std::filesystem::path& path);

struct MovieSpec {
    int width = 0, height = 0;
    int frames = 0;
    int fps = 25;
};

// Frames go in one at a time, as the picture is seen (srgbBytes); finish() completes the movie and renames it into
// place. A writer destroyed unfinished (a failure on the way) leaves no file at all. Throws InputError naming the
// path.
class MovieWriter {
public:
    MovieWriter(const std::filesystem::path& path, const MovieSpec& spec, std::string format);
    virtual ~MovieWriter() = default;
    void add(const Image& frame);  // spec.width x spec.height, at most spec.frames of them
    void finish();                 // after exactly spec.frames frames

protected:
    [[noreturn]] void fail(const std::string& why) const;
    const std::filesystem::path& temporary() const { return file_.temporary(); }
    const MovieSpec& spec() const { return spec_; }

private:
    virtual void write(const std::vector<unsigned char>& rgb, int index) = 0;  // 3 bytes a pixel from the top row
    virtual void close() = 0;                                                  // after the last frame

    PendingFile file_;
    MovieSpec spec_;
    std::string format_;
    int added_ = 0;
};

std::unique_ptr<MovieWriter> openGif(const std::filesystem::path& path, const MovieSpec& spec);
std::unique_ptr<MovieWriter> openMp4(const std::filesystem::path& path, const MovieSpec& spec);
// The writer of the path's format (movieFormat); refuses any other extension.
std::unique_ptr<MovieWriter> openMovie(const std::filesystem::path& path, const MovieSpec& spec);

}  // namespace vr
