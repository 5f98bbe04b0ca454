#include "volrender/movies/video_movie.h"

extern "C" {
#include <libavutil/log.h>
}

#include <stdexcept>

namespace vr {
namespace {
std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}
}  // namespace

void VideoMovie::fail(const std::string& why) { throw std::runtime_error(why); }

VideoMovie::VideoMovie(const char* path, const MovieSpec& spec, const char* encoder, const char* muxer,
                       const std::function<void(AVCodecContext&)>& configure)
    : spec_(spec) {
    av_log_set_level(AV_LOG_ERROR);  // encoders report their settings and statistics otherwise
    const AVCodec* codec = avcodec_find_encoder_by_name(encoder);
    if (!codec) fail(std::string("this libavcodec has no ") + encoder + " encoder");
    AVFormatContext* context = nullptr;
    if (int e = avformat_alloc_output_context2(&context, nullptr, muxer, path); e < 0)
        fail(avError(e));
    format_.reset(context);
    stream_ = avformat_new_stream(context, nullptr);
    codec_.reset(avcodec_alloc_context3(codec));
    if (!stream_ || !codec_) fail("out of memory");
    codec_->width = spec.width;
    codec_->height = spec.height;
    codec_->time_base = {1, spec.fps};
    codec_->framerate = {spec.fps, 1};
    configure(*codec_);
    if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    if (int e = avcodec_open2(codec_.get(), codec, nullptr); e < 0) fail(avError(e));
    if (int e = avcodec_parameters_from_context(stream_->codecpar, codec_.get()); e < 0) fail(avError(e));
    stream_->time_base = codec_->time_base;
    if (int e = avio_open(&format_->pb, path, AVIO_FLAG_WRITE); e < 0) fail(avError(e));
    if (int e = avformat_write_header(format_.get(), nullptr); e < 0) fail(avError(e));

    frame_.reset(av_frame_alloc());
    packet_.reset(av_packet_alloc());
    if (!frame_ || !packet_) fail("out of memory");
    frame_->format = codec_->pix_fmt;
    frame_->width = spec.width;
    frame_->height = spec.height;
    if (int e = av_frame_get_buffer(frame_.get(), 0); e < 0) fail(avError(e));
}

void VideoMovie::write(const std::vector<unsigned char>& rgb, int index) {
    if (int e = av_frame_make_writable(frame_.get()); e < 0) fail(avError(e));
    fill(rgb, *frame_);
    frame_->pts = index;
    encode(frame_.get());
}

void VideoMovie::close() {
    encode(nullptr);  // drains the encoder's delayed frames
    if (int e = av_write_trailer(format_.get()); e < 0) fail(avError(e));
    if (int e = avio_closep(&format_->pb); e < 0) fail(avError(e));
}

// Sends a frame (nullptr: the end) and muxes every packet the encoder has ready.
void VideoMovie::encode(const AVFrame* frame) {
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

}  // namespace vr
