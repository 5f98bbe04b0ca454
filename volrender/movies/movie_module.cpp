// volrender_movies.so's one entry (movie_encoder.h).
#include "volrender/movies/movie_encoder.h"
#include "volrender/movies/video_movie.h"

extern "C" vr::MovieEncoder* vrOpenMovieEncoder(vr::MovieFormat format, const char* path, const vr::MovieSpec& spec) {
    return (format == vr::MovieFormat::Gif ? vr::openGif(path, spec) : vr::openMp4(path, spec)).release();
}
