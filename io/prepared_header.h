// Reading the prepared file's header (internal to io/): the file, opened for checked reads from many threads, and
// everything its header says, checked against the file before any chunk is read.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/extent_code.h"
#include "core/prepared_volume.h"

namespace vr::prepared_detail {

// Reading: every problem becomes an InputError naming the file. pread() lets chunks be read from many threads.
class Reader {
public:
    explicit Reader(const std::filesystem::path& path);
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;

    InputError fail(const std::string& problem) const { return fileError(path_.string(), problem); }
    uint64_t size() const { return size_; }

    void read(uint64_t offset, void* to, std::size_t bytes, const std::string& what) const;

private:
    std::filesystem::path path_;
    uint64_t size_ = 0;
    int fd_ = -1;
};

// One block of a chunk in the file: a zstd frame of `stored` bytes at `at` (from the start of the file) that
// decompresses to `bytes`, and the CRC-32 of the frame.
struct BlockEntry {
    uint64_t at, stored, bytes;
    uint32_t crc;
};

struct ChunkEntry {
    uint64_t offset = 0, bytes = 0;  // of the first block (from the data section), and uncompressed
    uint64_t storedBytes = 0;        // of all its blocks
    uint64_t sliceBytes = 0;         // sliceBytesOf
    std::vector<BlockEntry> blocks;
};

// Everything the header says, checked against the file: all of the prepared volume but the chunks' contents.
struct Header {
    PreparedVolume prepared;  // grid, scalar type, classification numbers, region count and metadata
    std::size_t tableEntries = 0;
    std::optional<ScalarType> labelType;  // with a label map: its type, and its classes' count
    std::size_t labelEntries = 0;
    ExtentCode eacdCode = kDefaultExtentCode;
    std::map<std::string, ChunkEntry> chunks;  // by name
    std::vector<std::string> order;            // the chunks' names in the order of the chunk table
    uint64_t dataStart = 0;                    // where the chunks' offsets start
    uint64_t blockBytes = 0;                   // of every chunk's blocks but its last, uncompressed
};

// The header of the file `r` reads, checked: throws InputError (naming the file) for anything wrong with it.
Header readHeader(const Reader& r);

}  // namespace vr::prepared_detail
