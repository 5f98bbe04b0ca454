// Reading a file whose header may lie, for the checks in header_checks.h: every read is bounded by the file's
// size (a stated length beyond it fails instead of allocating or looping), and every failure is an InputError
// naming the file and the problem.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/errors.h"

namespace vr {

// The T stored at `offset` of `bytes` (which must hold it) in byte order `order`.
template <typename T>
T valueAt(std::string_view bytes, std::size_t offset, std::endian order = std::endian::little) {
    static_assert(std::is_arithmetic_v<T>);
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), bytes.data() + offset, sizeof(T));
    if (order != std::endian::native) std::reverse(raw.begin(), raw.end());
    return std::bit_cast<T>(raw);
}

// One open file, read from a position that starts at byte 0 and never passes the file's end.
class BoundedReader {
public:
    // Opens `path`, whose problems fail() tells as "PATH: SUBJECT: PROBLEM" (subject: "invalid NRRD file").
    // Throws InputError "PATH: cannot open" or "PATH: cannot read: REASON".
    BoundedReader(std::filesystem::path path, std::string subject);

    // A file that this one names (a header's detached data), with the same subject. Failing to open it is this
    // file's problem: "PATH: SUBJECT: cannot read data file OTHER: REASON".
    BoundedReader dataFile(const std::filesystem::path& other) const;

    const std::filesystem::path& path() const { return path_; }
    std::uint64_t size() const { return size_; }
    std::uint64_t position() const { return position_; }
    std::uint64_t remaining() const { return size_ - position_; }

    // "PATH: SUBJECT: PROBLEM", for the caller to throw.
    InputError fail(const std::string& problem) const;

    // Each of these fails, naming `what` they were reading, where the file ends first.
    void seek(std::uint64_t at, const std::string& what);
    void require(std::uint64_t count, const std::string& what) const;
    void skip(std::uint64_t count, const std::string& what);
    std::string bytes(std::size_t count, const std::string& what);
    void bytes(void* to, std::size_t count, const std::string& what);
    template <typename T>
    T littleEndian(const std::string& what) {
        if (remaining() < sizeof(T)) throw fail("it ends in " + what);
        return valueAt<T>(bytes(sizeof(T), what), 0);
    }

    // Up to `count` bytes (fewer where the file ends), into `to`; returns how many.
    std::size_t readUpTo(void* to, std::size_t count);
    std::string bytesUpTo(std::size_t count);

    // The next line of a text header, without its line break; nullopt at the end of the file. The second form
    // fails with `beyondLimit` for a line that does not end (with a line break, or the file's end counted as one)
    // within the file's first `limit` bytes, so that no header is read further than its format allows.
    std::optional<std::string> line();
    std::optional<std::string> line(std::uint64_t limit, const std::string& beyondLimit);
    // Whether the line last read ended with a line break rather than the file's end.
    bool lineEnded() const { return lineEnded_; }

    // How many whitespace-separated words follow, counted up to `most` (text data: one value a word).
    std::uint64_t countWords(std::uint64_t most);

private:
    struct Unopened {};
    BoundedReader(std::filesystem::path path, std::string subject, Unopened);
    std::string open();  // the problem opening the file, or "" once it is open
    int next();          // the next byte, or EOF at the end of the file

    std::filesystem::path path_;
    std::string subject_;
    std::ifstream in_;
    std::uint64_t size_ = 0, position_ = 0;
    bool lineEnded_ = false;
};

}  // namespace vr
