// The MP4: H.264 (libavcodec's libx264 encoder, in Debian's libavcodec) in 4:2:0 at a constant quality, the frames
// converted from sRGB RGB by libswscale with the BT.709 matrix the stream is tagged with, muxed by libavformat.
extern "C" {
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "volrender/movies/video_movie.h"

namespace vr {
namespace {

// libx264's constant rate factor: 0 is lossless, 23 its default; at 18 the frames look as rendered.
constexpr const char* kQuality = "18";

struct SwsFree {
    void operator()(SwsContext* s) const { sws_freeContext(s); }
};

void configureH264(AVCodecContext& codec) {
    codec.pix_fmt = AV_PIX_FMT_YUV420P;
    codec.color_range = AVCOL_RANGE_MPEG;
    codec.colorspace = AVCOL_SPC_BT709;
    codec.color_primaries = AVCOL_PRI_BT709;
    codec.color_trc = AVCOL_TRC_IEC61966_2_1;  // the frames are sRGB-encoded
    av_opt_set(codec.priv_data, "crf", kQuality, 0);
}

class Mp4Movie final : public VideoMovie {
public:
    Mp4Movie(const char* path, const MovieSpec& spec) : VideoMovie(path, spec, "libx264", "mp4", configureH264) {
        toYuv_.reset(sws_getContext(spec.width, spec.height, AV_PIX_FMT_RGB24, spec.width, spec.height,
                                    AV_PIX_FMT_YUV420P, SWS_BICUBIC | SWS_ACCURATE_RND, nullptr, nullptr, nullptr));
        if (!toYuv_) fail("no RGB to YUV 4:2:0 conversion");
        const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
        sws_setColorspaceDetails(toYuv_.get(), bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);  // full-range RGB in
    }

private:
    void fill(const std::vector<unsigned char>& rgb, AVFrame& frame) override {
        const uint8_t* source[1] = {rgb.data()};
        const int stride[1] = {3 * spec().width};
        sws_scale(toYuv_.get(), source, stride, 0, spec().height, frame.data, frame.linesize);
    }

    std::unique_ptr<SwsContext, SwsFree> toYuv_;
};

}  // namespace

std::unique_ptr<MovieEncoder> openMp4(const char* path, const MovieSpec& spec) {
    return std::make_unique<Mp4Movie>(path, spec);
}

}  // namespace vr
