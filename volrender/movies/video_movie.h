// What the movies FFmpeg writes share: one video stream encoded by libavcodec and muxed by libavformat, each frame
// lasting one tick of 1/fps. A subclass converts the frames into its codec's pixel format.
#pragma once
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <functional>
#include <memory>
#include <string>

#include "volrender/movies/movie_encoder.h"

namespace vr {

class VideoMovie : public MovieEncoder {
protected:
    // Writes `path`; `encoder` and `muxer` by their FFmpeg names; `configure` sets the codec's pixel format and
    // options before it opens (the size and rate are set already).
    VideoMovie(const char* path, const MovieSpec& spec, const char* encoder, const char* muxer,
               const std::function<void(AVCodecContext&)>& configure);
    [[noreturn]] static void fail(const std::string& why);
    const MovieSpec& spec() const { return spec_; }

private:
    // The frame's buffers are writable and in the codec's pixel format; rgb: 3 bytes a pixel from the top row.
    virtual void fill(const std::vector<unsigned char>& rgb, AVFrame& frame) = 0;

    void write(const std::vector<unsigned char>& rgb, int index) final;
    void close() final;
    void encode(const AVFrame* frame);

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

    MovieSpec spec_;
    // Destroyed unfinished, the file is closed here (the caller removes it).
    std::unique_ptr<AVFormatContext, FormatFree> format_;
    AVStream* stream_ = nullptr;  // owned by format_
    std::unique_ptr<AVCodecContext, CodecFree> codec_;
    std::unique_ptr<AVFrame, FrameFree> frame_;
    std::unique_ptr<AVPacket, PacketFree> packet_;
};

// The two movies, each in its own file.
std::unique_ptr<MovieEncoder> openGif(const char* path, const MovieSpec& spec);
std::unique_ptr<MovieEncoder> openMp4(const char* path, const MovieSpec& spec);

}  // namespace vr
