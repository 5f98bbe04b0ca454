// The animated GIF: libavcodec's GIF encoder, each frame with its own palette of at most 256 colours (median cut),
// muxed by libavformat's GIF muxer, which loops the movie forever.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "volrender/movies/gif_palette.h"
#include "volrender/movies/video_movie.h"

namespace vr {
namespace {

class GifMovie final : public VideoMovie {
public:
    GifMovie(const char* path, const MovieSpec& spec)
        : VideoMovie(path, spec, "gif", "gif", [](AVCodecContext& codec) { codec.pix_fmt = AV_PIX_FMT_PAL8; }) {}

private:
    void fill(const std::vector<unsigned char>& rgb, AVFrame& frame) override {
        const PalettedFrame paletted = medianCut(rgb);
        // The palette's 256 entries are 0xAARRGGBB words; all opaque, so that the encoder sees no transparent colour.
        auto* palette = reinterpret_cast<std::uint32_t*>(frame.data[1]);
        std::fill(palette, palette + 256, 0xff000000u);
        for (std::size_t i = 0; i < paletted.palette.size(); ++i) {
            const auto& [r, g, b] = paletted.palette[i];
            palette[i] = 0xff000000u | std::uint32_t(r) << 16 | std::uint32_t(g) << 8 | b;
        }
        const int w = spec().width;
        for (int y = 0; y < spec().height; ++y)
            std::memcpy(frame.data[0] + std::ptrdiff_t(y) * frame.linesize[0], &paletted.indices[std::size_t(y) * w],
                        std::size_t(w));
    }
};

}  // namespace

std::unique_ptr<MovieEncoder> openGif(const char* path, const MovieSpec& spec) {
    return std::make_unique<GifMovie>(path, spec);
}

}  // namespace vr
