// Movies of an orbit's views: an animated GIF or an H.264 MP4, frame by frame as they are rendered, under a
// temporary name until the last frame is in. The encoding (FFmpeg) is volrender's movie module's
// (volrender/movies/), loaded only when a movie is written.
#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "io/atomic_file.h"
#include "render/image.h"
#include "volrender/movies/movie_encoder.h"

namespace vr {

// By extension, any case: .gif, .mp4; nothing for any other.
std::optional<MovieFormat> movieFormat(const std::filesystem::path& path);

// Loads the movie module, so that a run that cannot write its movie fails before it renders. Throws
// std::runtime_error naming the module's file and why it cannot be loaded.
void requireMovieModule();

// Frames go in one at a time, as the picture is seen (srgbBytes); finish() completes the movie and renames it into
// place. A writer destroyed unfinished (a failure on the way) leaves no file at all. Throws InputError naming the
// path, for a path that is not a movie (movieFormat) too.
class MovieWriter {
public:
    MovieWriter(const std::filesystem::path& path, const MovieSpec& spec);
    void add(const Image& frame);  // spec.width x spec.height, at most spec.frames of them
    void finish();                 // after exactly spec.frames frames

private:
    [[noreturn]] void fail(const std::string& why) const;

    PendingFile file_;
    MovieSpec spec_;
    std::string format_;  // its name in messages
    std::unique_ptr<MovieEncoder> encoder_;  // destroyed first: it closes the temporary before file_ removes it
    int added_ = 0;
};

}  // namespace vr
