#include "volrender/cmd/movie_writer.h"

#include <algorithm>
#include <cctype>

#include "core/errors.h"

namespace vr {

std::optional<MovieFormat> movieFormat(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gif") return MovieFormat::Gif;
    if (ext == ".mp4") return MovieFormat::Mp4;
    return std::nullopt;
}

MovieWriter::MovieWriter(const std::filesystem::path& path, const MovieSpec& spec, std::string format)
    : file_(path), spec_(spec), format_(std::move(format)) {}

void MovieWriter::fail(const std::string& why) const {
    throw fileError(file_.path().string(), "cannot write the " + format_ + ": " + why);
}

void MovieWriter::add(const Image& frame) {
    if (added_ == spec_.frames) fail("more frames than the " + std::to_string(spec_.frames) + " announced");
    if (frame.width != spec_.width || frame.height != spec_.height)
        fail("a frame of " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " in a movie of " +
             std::to_string(spec_.width) + "x" + std::to_string(spec_.height));
    write(srgbBytes(frame), added_);
    ++added_;
}

void MovieWriter::finish() {
    if (added_ != spec_.frames)
        fail(std::to_string(added_) + " frames of the " + std::to_string(spec_.frames) + " announced");
    close();
    file_.commit();
}

std::unique_ptr<MovieWriter> openMovie(const std::filesystem::path& path, const MovieSpec& spec) {
    const std::optional<MovieFormat> format = movieFormat(path);
    if (!format) throw fileError(path.string(), "not a movie: movies are written as .gif or .mp4");
    return *format == MovieFormat::Gif ? openGif(path, spec) : openMp4(path, spec);
}

}  // namespace vr
