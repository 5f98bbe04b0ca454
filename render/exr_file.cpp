#include "render/exr_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstdint>
#include <exception>
#include <string>

#include "core/errors.h"
#include "io/atomic_file.h"

namespace vr {
namespace fs = std::filesystem;

namespace {
constexpr const char* kChannels[4] = {"R", "G", "B", "A"};
constexpr std::size_t kPixelBytes = 4 * sizeof(float);
}  // namespace

void writeExr(const fs::path& path, const Image& image) {
    writePathAtomically(path, [&](const fs::path& tmp) {
        try {
            Imf::Header header(image.width, image.height);
            Imf::FrameBuffer frame;
            for (int c = 0; c < 4; ++c) {
                header.channels().insert(kChannels[c], Imf::Channel(Imf::FLOAT));
                // OpenEXR's slices are writable in general; this one is only read.
                char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgba.data() + c));
                frame.insert(kChannels[c], Imf::Slice(Imf::FLOAT, base, kPixelBytes, kPixelBytes * image.width));
            }
            Imf::OutputFile out(tmp.c_str(), header);
            out.setFrameBuffer(frame);
            out.writePixels(image.height);
        } catch (const std::exception& e) {
            throw fileError(path.string(), std::string("cannot write EXR: ") + e.what());
        }
    });
}

Image readExr(const fs::path& path) {
    try {
        Imf::InputFile in(path.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1,
                           height = std::int64_t(window.max.y) - window.min.y + 1;
        if (width <= 0 || height <= 0 || width * height > kMaxImageFilePixels)
            throw fileError(path.string(), "an EXR of " + std::to_string(width) + "x" + std::to_string(height) +
                                               " pixels is empty or more than an image file may hold here");
        Image image{int(width), int(height)};
        const Imf::ChannelList& channels = in.header().channels();
        const bool grey = !channels.findChannel("R") && channels.findChannel("Y");
        Imf::FrameBuffer frame;
        for (int c = 0; c < 4; ++c) {
            if (grey && (c == 1 || c == 2)) continue;  // copied from R below
            // The data window need not start at (0, 0): the slice's origin is its corner.
            char* base = reinterpret_cast<char*>(image.rgba.data() + c) -
                         (std::ptrdiff_t(window.min.y) * image.width + window.min.x) * std::ptrdiff_t(kPixelBytes);
            const double missing = c == 3 ? 1.0 : 0.0;
            frame.insert(grey && c == 0 ? "Y" : kChannels[c],
                         Imf::Slice(Imf::FLOAT, base, kPixelBytes, kPixelBytes * image.width, 1, 1, missing));
        }
        in.setFrameBuffer(frame);
        in.readPixels(window.min.y, window.max.y);
        if (grey)
            for (std::size_t p = 0; p < image.rgba.size(); p += 4)
                image.rgba[p + 1] = image.rgba[p + 2] = image.rgba[p];
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw fileError(path.string(), std::string("cannot read EXR: ") + e.what());
    }
}

}  // namespace vr
