#include "volrender/cmd/movie_writer.h"

#include "core/errors.h"
#include "core/lower_case.h"
#include "tools/runtime_module.h"

namespace vr {
namespace {

// FFmpeg's libraries, with the codecs they load, are over a hundred shared libraries: the module keeps them out of
// volrender's start.
decltype(vrOpenMovieEncoder)* openEncoder() {
    static decltype(vrOpenMovieEncoder)* const open = moduleFunction<decltype(vrOpenMovieEncoder)>(
        "volrender_movies", "vrOpenMovieEncoder", "writes movies (.gif, .mp4)");
    return open;
}

}  // namespace

std::optional<MovieFormat> movieFormat(const std::filesystem::path& path) {
    const std::string ext = lowerCase(path.extension().string());
    if (ext == ".gif") return MovieFormat::Gif;
    if (ext == ".mp4") return MovieFormat::Mp4;
    return std::nullopt;
}

void requireMovieModule() { openEncoder(); }

MovieWriter::MovieWriter(const std::filesystem::path& path, const MovieSpec& spec) : file_(path), spec_(spec) {
    const std::optional<MovieFormat> format = movieFormat(path);
    if (!format) throw fileError(path.string(), "not a movie: movies are written as .gif or .mp4");
    format_ = *format == MovieFormat::Gif ? "GIF" : "MP4";
    try {
        encoder_.reset(openEncoder()(*format, file_.temporary().c_str(), spec));
    } catch (const std::exception& e) {
        fail(e.what());
    }
}

void MovieWriter::fail(const std::string& why) const {
    throw fileError(file_.path().string(), "cannot write the " + format_ + ": " + why);
}

void MovieWriter::add(const Image& frame) {
    if (added_ == spec_.frames) fail("more frames than the " + std::to_string(spec_.frames) + " announced");
    if (frame.width != spec_.width || frame.height != spec_.height)
        fail("a frame of " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " in a movie of " +
             std::to_string(spec_.width) + "x" + std::to_string(spec_.height));
    try {
        encoder_->write(srgbBytes(frame), added_);
    } catch (const std::exception& e) {
        fail(e.what());
    }
    ++added_;
}

void MovieWriter::finish() {
    if (added_ != spec_.frames)
        fail(std::to_string(added_) + " frames of the " + std::to_string(spec_.frames) + " announced");
    try {
        encoder_->close();
    } catch (const std::exception& e) {
        fail(e.what());
    }
    file_.commit();
}

}  // namespace vr
