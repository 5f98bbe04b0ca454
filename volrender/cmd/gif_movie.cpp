// The animated GIF: one subimage a frame, each with the palette of 256 colours that OpenImageIO's GIF writer
// chooses for it.
#include <OpenImageIO/imageio.h>

#include "volrender/cmd/movie_writer.h"

namespace vr {
namespace {

class GifMovie final : public MovieWriter {
public:
    GifMovie(const std::filesystem::path& path, const MovieSpec& spec) : MovieWriter(path, spec, "GIF") {
        out_ = OIIO::ImageOutput::create(temporary().string());
        if (!out_) fail("no GIF writer in this OpenImageIO: " + OIIO::geterror());
        OIIO::ImageSpec frame(spec.width, spec.height, 3, OIIO::TypeDesc::UINT8);
        frame.attribute("oiio:ColorSpace", "sRGB");
        const int rate[2] = {spec.fps, 1};
        frame.attribute("FramesPerSecond", OIIO::TypeRational, rate);
        frames_.assign(std::size_t(spec.frames), frame);
    }
    ~GifMovie() override {
        if (open_) out_->close();  // unfinished: the temporary is removed with the base
    }

private:
    // The writer is told every frame up front, then given them one by one (AppendSubimage).
    void write(const std::vector<unsigned char>& rgb, int index) override {
        const std::string name = temporary().string();
        const bool opened = index == 0 ? out_->open(name, int(frames_.size()), frames_.data())
                                       : out_->open(name, frames_[std::size_t(index)], OIIO::ImageOutput::AppendSubimage);
        open_ = open_ || opened;
        if (!opened || !out_->write_image(OIIO::TypeDesc::UINT8, rgb.data())) fail(out_->geterror());
    }

    void close() override {
        open_ = false;
        if (!out_->close()) fail(out_->geterror());
    }

    std::unique_ptr<OIIO::ImageOutput> out_;
    std::vector<OIIO::ImageSpec> frames_;
    bool open_ = false;
};

}  // namespace

std::unique_ptr<MovieWriter> openGif(const std::filesystem::path& path, const MovieSpec& spec) {
    return std::make_unique<GifMovie>(path, spec);
}

}  // namespace vr
