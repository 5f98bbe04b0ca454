// Where the views of a render go: image files (NAME.EXT for one view, NAME_007.EXT for view 7 of an orbit), or the
// frames of one movie (NAME.gif, NAME.mp4) that appears when its last frame is in.
#pragma once
#include <memory>
#include <string>

#include "volrender/cmd/movie_writer.h"

namespace vr {

// Refuses, before anything is rendered, a path that is neither a movie nor an image format (isImageFormat), and a
// movie its codec cannot hold (an MP4 needs an even width and height): InputError naming `flag` and the path. For a
// movie, loads the movie module (std::runtime_error naming `flag`, the path and the module's file where it cannot).
void checkViewOutput(const std::string& path, const char* flag, int width, int height);

// The file that holds view `view` of `views` written to `path`: NAME_007.EXT for view 7 of an orbit of images; the
// path itself for a single view or a movie.
std::string viewFileName(const std::string& path, int view, int views);

class ViewOutput {
public:
    // `movie` gives the size, the frame count (the views) and the frame rate.
    ViewOutput(std::string path, const MovieSpec& movie);
    bool isMovie() const { return movie_ != nullptr; }
    std::string name(int view) const;  // the file that holds it
    void add(int view, const Image& image);
    void finish();  // the movie appears (images are written as they come)

private:
    std::string path_;
    int views_;
    std::unique_ptr<MovieWriter> movie_;
};

}  // namespace vr
