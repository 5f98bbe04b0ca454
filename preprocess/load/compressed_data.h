// What compressed data inside a checked file hold, read through the file's BoundedReader.
#pragma once
#include <cstdint>
#include <string>

#include "preprocess/load/bounded_reader.h"

namespace vr {

// How data are packed: what gzread reads (gzip members, or plain bytes without the gzip magic) or what MetaIO
// inflates (zlib or gzip).
enum class Compression { GzipOrPlain, ZlibOrGzip };

// The bytes that the compressed data starting `offset` bytes into `file` (and at most `compressedBytes` long)
// decompress to, counted by decompressing them up to `needed` (the count returned is at most that): what a reader
// can really fill, found in time and memory bounded by `needed`. Throws the file's InputError for a corrupt
// stream; data that end early are simply counted short.
std::uintmax_t decompressedBytes(BoundedReader& file, std::uintmax_t offset, std::uintmax_t needed,
                                 Compression compression, std::uintmax_t compressedBytes = UINTMAX_MAX);

// The first `count` bytes (fewer where the data end) that gzread gives for `file`, as VTK's readers of gzipped
// files read them: gzip members decompressed, or the bytes as they are without the gzip magic. Throws the file's
// InputError for a corrupt stream that gives nothing.
std::string gzreadBytes(const BoundedReader& file, std::size_t count);

}  // namespace vr
