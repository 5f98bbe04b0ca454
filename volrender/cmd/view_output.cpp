#include "volrender/cmd/view_output.h"

#include <cstdio>
#include <stdexcept>

#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;

void checkViewOutput(const std::string& path, const char* flag, int width, int height) {
    const std::optional<MovieFormat> movie = movieFormat(path);
    if (movie == MovieFormat::Mp4 && (width % 2 || height % 2))
        throw InputError(std::string(flag) + " " + path + ": an MP4 (H.264 in 4:2:0) needs an even width and height, "
                         "not --size " + std::to_string(width) + "x" + std::to_string(height));
    if (!movie && !isImageFormat(path))
        throw InputError(std::string(flag) + " " + path +
                         ": neither an image format (.png, .exr) nor a movie (.gif, .mp4)");
    if (!movie) return;
    try {
        requireMovieModule();
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string(flag) + " " + path + ": " + e.what());
    }
}

ViewOutput::ViewOutput(std::string path, const MovieSpec& movie) : path_(std::move(path)), views_(movie.frames) {
    if (movieFormat(path_)) movie_ = std::make_unique<MovieWriter>(path_, movie);
}

std::string viewFileName(const std::string& path, int view, int views) {
    if (views == 1 || movieFormat(path)) return path;
    const fs::path p(path);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "_%03d", view);
    return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

std::string ViewOutput::name(int view) const { return viewFileName(path_, view, views_); }

void ViewOutput::add(int view, const Image& image) {
    if (movie_)
        movie_->add(image);
    else
        writeImage(name(view), image);
}

void ViewOutput::finish() {
    if (movie_) movie_->finish();
}

}  // namespace vr
