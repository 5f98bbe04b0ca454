#include "support/movie_frames.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "render/png_file.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

namespace vr::test {
namespace fs = std::filesystem;

Frames readImageBytes(const fs::path& path) {
    const PngPixels png = readPng(path);
    return {png.width, png.height, 0, {rgbOf(png)}};
}

Frames readMovieFrames(const fs::path& path) {
    AVFormatContext* format = nullptr;
    if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0)
        throw std::runtime_error("cannot open " + path.string());
    const std::unique_ptr<AVFormatContext*, void (*)(AVFormatContext**)> closeFormat(&format, avformat_close_input);
    if (avformat_find_stream_info(format, nullptr) < 0) throw std::runtime_error("no stream info");
    const AVCodec* decoder = nullptr;
    const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
    if (stream < 0) throw std::runtime_error("no video stream in " + path.string());
    AVCodecContext* codec = avcodec_alloc_context3(decoder);
    const std::unique_ptr<AVCodecContext*, void (*)(AVCodecContext**)> freeCodec(&codec, avcodec_free_context);
    avcodec_parameters_to_context(codec, format->streams[stream]->codecpar);
    if (avcodec_open2(codec, decoder, nullptr) < 0) throw std::runtime_error("cannot open the decoder");
    AVFrame* frame = av_frame_alloc();
    const std::unique_ptr<AVFrame*, void (*)(AVFrame**)> freeFrame(&frame, av_frame_free);
    AVPacket* packet = av_packet_alloc();
    const std::unique_ptr<AVPacket*, void (*)(AVPacket**)> freePacket(&packet, av_packet_free);

    Frames frames;
    frames.width = codec->width;
    frames.height = codec->height;
    frames.fps = av_q2d(format->streams[stream]->avg_frame_rate);
    SwsContext* toRgb = nullptr;
    auto receive = [&] {
        while (avcodec_receive_frame(codec, frame) == 0) {
            // YUV to full-range RGB with the matrix and range the stream is tagged with.
            toRgb = sws_getCachedContext(toRgb, frame->width, frame->height, AVPixelFormat(frame->format),
                                         frame->width, frame->height, AV_PIX_FMT_RGB24,
                                         SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr, nullptr,
                                         nullptr);
            const int* matrix =
                sws_getCoefficients(frame->colorspace == AVCOL_SPC_BT709 ? SWS_CS_ITU709 : SWS_CS_DEFAULT);
            sws_setColorspaceDetails(toRgb, matrix, frame->color_range == AVCOL_RANGE_JPEG, matrix, 1, 0, 1 << 16,
                                     1 << 16);
            std::vector<unsigned char> rgb(std::size_t(frame->width) * frame->height * 3);
            uint8_t* planes[1] = {rgb.data()};
            const int stride[1] = {3 * frame->width};
            sws_scale(toRgb, frame->data, frame->linesize, 0, frame->height, planes, stride);
            frames.rgb.push_back(std::move(rgb));
        }
    };
    while (av_read_frame(format, packet) >= 0) {
        if (packet->stream_index == stream) avcodec_send_packet(codec, packet);
        av_packet_unref(packet);
        receive();
    }
    avcodec_send_packet(codec, nullptr);
    receive();
    sws_freeContext(toRgb);
    return frames;
}

FrameDifference frameDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
    if (a.size() != b.size()) throw std::runtime_error("frames of different sizes");
    FrameDifference d;
    double sum = 0, beyond = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const int e = std::abs(int(a[i]) - int(b[i]));
        sum += e;
        beyond += e > 16;
        d.max = std::max(d.max, e);
    }
    d.mean = a.empty() ? 0 : sum / double(a.size());
    d.beyond16 = a.empty() ? 0 : beyond / double(a.size());
    return d;
}

}  // namespace vr::test
