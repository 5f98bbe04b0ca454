// The MP4: H.264 (libavcodec's libx264 encoder, in Debian's libavcodec) in 4:2:0 at a constant quality, the frames
// converted from sRGB RGB by libswscale with the BT.709 matrix the stream is tagged with, muxed by libavformat.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "volrender/cmd/movie_writer.h"

namespace vr {
namespace {

// libx264's constant rate factor: 0 is lossless, 23 its default; at 18 the frames look as rendered.
constexpr const char* kQuality = "18";

std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

struct FormatFree {
    void operator()(AVFormatContext* f) const {
        if (f->pb) avio_closep(&f->pb);
        avformat_free_context(f);
    }
};
struct CodecFree {
    void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
    void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct SwsFree {
    void operator()(SwsContext* s) const { sws_freeContext(s); }
};

class Mp4Movie final : public MovieWriter {
public:
    Mp4Movie(const std::filesystem::path& path, const MovieSpec& spec) : MovieWriter(path, spec, "MP4") {
        av_log_set_level(AV_LOG_ERROR);  // libx264 reports its settings and statistics otherwise
        const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
        if (!codec) fail("this libavcodec has no H.264 encoder (libx264)");
        AVFormatContext* format = nullptr;
        if (int e = avformat_alloc_output_context2(&format, nullptr, "mp4", temporary().c_str()); e < 0)
            fail(avError(e));
        format_.reset(format);
        stream_ = avformat_new_stream(format, nullptr);
        codec_.reset(avcodec_alloc_context3(codec));
        if (!stream_ || !codec_) fail("out of memory");
        codec_->width = spec.width;
        codec_->height = spec.height;
        codec_->time_base = {1, spec.fps};
        codec_->framerate = {spec.fps, 1};
        codec_->pix_fmt = AV_PIX_FMT_YUV420P;
        codec_->color_range = AVCOL_RANGE_MPEG;
        codec_->colorspace = AVCOL_SPC_BT709;
        codec_->color_primaries = AVCOL_PRI_BT709;
        codec_->color_trc = AVCOL_TRC_IEC61966_2_1;  // the frames are sRGB-encoded
        if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
        av_opt_set(codec_->priv_data, "crf", kQuality, 0);
        if (int e = avcodec_open2(codec_.get(), codec, nullptr); e < 0) fail(avError(e));
        if (int e = avcodec_parameters_from_context(stream_->codecpar, codec_.get()); e < 0) fail(avError(e));
        stream_->time_base = codec_->time_base;
        if (int e = avio_open(&format_->pb, temporary().c_str(), AVIO_FLAG_WRITE); e < 0) fail(avError(e));
        if (int e = avformat_write_header(format_.get(), nullptr); e < 0) fail(avError(e));

        frame_.reset(av_frame_alloc());
        packet_.reset(av_packet_alloc());
        if (!frame_ || !packet_) fail("out of memory");
        frame_->format = codec_->pix_fmt;
        frame_->width = spec.width;
        frame_->height = spec.height;
        if (int e = av_frame_get_buffer(frame_.get(), 0); e < 0) fail(avError(e));
        toYuv_.reset(sws_getContext(spec.width, spec.height, AV_PIX_FMT_RGB24, spec.width, spec.height,
                                    codec_->pix_fmt, SWS_BICUBIC | SWS_ACCURATE_RND, nullptr, nullptr, nullptr));
        if (!toYuv_) fail("no RGB to YUV 4:2:0 conversion");
        const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
        sws_setColorspaceDetails(toYuv_.get(), bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);  // full-range RGB in
    }

private:
    void write(const std::vector<unsigned char>& rgb, int index) override {
        if (int e = av_frame_make_writable(frame_.get()); e < 0) fail(avError(e));
        const uint8_t* source[1] = {rgb.data()};
        const int stride[1] = {3 * spec().width};
        sws_scale(toYuv_.get(), source, stride, 0, spec().height, frame_->data, frame_->linesize);
        frame_->pts = index;
        encode(frame_.get());
    }

    void close() override {
        encode(nullptr);  // drains the encoder's delayed frames
        if (int e = av_write_trailer(format_.get()); e < 0) fail(avError(e));
        if (int e = avio_closep(&format_->pb); e < 0) fail(avError(e));
    }

    // Sends a frame (nullptr: the end) and muxes every packet the encoder has ready.
    void encode(const AVFrame* frame) {
        if (int e = avcodec_send_frame(codec_.get(), frame); e < 0) fail(avError(e));
        for (;;) {
            const int e = avcodec_receive_packet(codec_.get(), packet_.get());
            if (e == AVERROR(EAGAIN) || e == AVERROR_EOF) return;
            if (e < 0) fail(avError(e));
            // Each frame lasts one tick of 1/fps: without it the muxer's edit list would end at the last frame's
            // start, and players would drop that frame.
            packet_->duration = 1;
            av_packet_rescale_ts(packet_.get(), codec_->time_base, stream_->time_base);
            packet_->stream_index = stream_->index;
            if (int w = av_interleaved_write_frame(format_.get(), packet_.get()); w < 0) fail(avError(w));
        }
    }

    // Destroyed unfinished, the file is closed here and the temporary removed with the base.
    std::unique_ptr<AVFormatContext, FormatFree> format_;
    AVStream* stream_ = nullptr;  // owned by format_
    std::unique_ptr<AVCodecContext, CodecFree> codec_;
    std::unique_ptr<AVFrame, FrameFree> frame_;
    std::unique_ptr<AVPacket, PacketFree> packet_;
    std::unique_ptr<SwsContext, SwsFree> toYuv_;
};

}  // namespace

std::unique_ptr<MovieWriter> openMp4(const std::filesystem::path& path, const MovieSpec& spec) {
    return std::make_unique<Mp4Movie>(path, spec);
}

}  // namespace vr
