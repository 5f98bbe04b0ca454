// What volrender and its movie module (volrender_movies.so, tools/runtime_module.h) share: the movie formats, a
// movie's size and rate, and the one entry that opens an encoder. The module holds everything that needs FFmpeg;
// volrender loads it only to write a movie.
#pragma once
#include <vector>

namespace vr {

enum class MovieFormat { Gif, Mp4 };

struct MovieSpec {
    int width = 0, height = 0;
    int frames = 0;
    int fps = 25;
};

// Encodes frames into one file as they come. Failures throw std::runtime_error saying what failed; the caller names
// the file.
class MovieEncoder {
public:
    virtual ~MovieEncoder() = default;  // closes the file, finished or not
    // The frame `index` (from 0, in order): spec.width x spec.height pixels of 3 bytes (sRGB), from the top row.
    virtual void write(const std::vector<unsigned char>& rgb, int index) = 0;
    virtual void close() = 0;  // after the last frame: the file is complete
};

}  // namespace vr

// The module's entry: a new encoder writing `format` to the file `path` (the caller owns it). Throws as above.
extern "C" vr::MovieEncoder* vrOpenMovieEncoder(vr::MovieFormat format, const char* path, const vr::MovieSpec& spec);
