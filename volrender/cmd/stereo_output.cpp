#include "volrender/cmd/stereo_output.h"

#include <algorithm>
#include <filesystem>

#include "core/errors.h"

namespace vr {

StereoLayout parseStereoLayout(std::string_view name) {
    if (name == "separate") return StereoLayout::Separate;
    if (name == "side-by-side") return StereoLayout::SideBySide;
    if (name == "top-bottom") return StereoLayout::TopBottom;
    if (name == "anaglyph") return StereoLayout::Anaglyph;
    throw InputError("--stereo-layout '" + std::string(name) +
                     "': expected separate, side-by-side, top-bottom or anaglyph");
}

std::pair<int, int> frameSize(int width, int height, std::optional<StereoLayout> layout) {
    if (layout == StereoLayout::SideBySide) return {2 * width, height};
    if (layout == StereoLayout::TopBottom) return {width, 2 * height};
    return {width, height};
}

Image composePair(const Image& left, const Image& right, StereoLayout layout) {
    const auto [width, height] = frameSize(left.width, left.height, layout);
    Image out(width, height);
    for (int y = 0; y < left.height; ++y)
        for (int x = 0; x < left.width; ++x) {
            const float* l = left.pixel(x, y);
            const float* r = right.pixel(x, y);
            if (layout == StereoLayout::Anaglyph) {
                float* o = out.pixel(x, y);
                o[0] = l[0], o[1] = r[1], o[2] = r[2], o[3] = std::max(l[3], r[3]);
                continue;
            }
            std::copy(l, l + 4, out.pixel(x, y));
            const bool beside = layout == StereoLayout::SideBySide;
            std::copy(r, r + 4, out.pixel(beside ? x + left.width : x, beside ? y : y + left.height));
        }
    return out;
}

std::string eyePath(const std::string& path, std::string_view eye) {
    const std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + "_" + std::string(eye) + p.extension().string())).string();
}

namespace {

// The outputs a frame goes to: NAME_left.EXT and NAME_right.EXT for separate eyes, else NAME.EXT.
std::vector<std::string> outputPaths(const std::string& path, std::optional<StereoLayout> layout) {
    if (layout == StereoLayout::Separate) return {eyePath(path, "left"), eyePath(path, "right")};
    return {path};
}

}  // namespace

std::vector<std::string> frameFiles(const std::string& path, int views, std::optional<StereoLayout> layout) {
    std::vector<std::string> files;
    for (int view = 0; view < (movieFormat(path) ? 1 : views); ++view)
        for (const std::string& output : outputPaths(path, layout))
            files.push_back(viewFileName(output, view, views));
    return files;
}

FrameOutput::FrameOutput(const std::string& path, const MovieSpec& movie, std::optional<StereoLayout> layout)
    : layout_(layout) {
    MovieSpec frame = movie;  // one eye's size in each of two outputs, or the pair's frame in one
    std::tie(frame.width, frame.height) = frameSize(movie.width, movie.height, layout);
    for (const std::string& output : outputPaths(path, layout)) outputs_.emplace_back(output, frame);
}

std::string FrameOutput::name(int view) const {
    std::string names;
    for (const ViewOutput& o : outputs_) names += (names.empty() ? "" : " + ") + o.name(view);
    return names;
}

void FrameOutput::add(int view, const std::vector<Image>& images) {
    if (!layout_) return outputs_.front().add(view, images.front());
    if (*layout_ != StereoLayout::Separate)
        return outputs_.front().add(view, composePair(images[0], images[1], *layout_));
    outputs_[0].add(view, images[0]);
    outputs_[1].add(view, images[1]);
}

void FrameOutput::finish() {
    for (ViewOutput& o : outputs_) o.finish();
}

}  // namespace vr
