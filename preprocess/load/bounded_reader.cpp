#include "preprocess/load/bounded_reader.h"

#include <cerrno>
#include <system_error>

#include "core/printable_text.h"

namespace vr {
namespace fs = std::filesystem;

BoundedReader::BoundedReader(fs::path path, std::string subject, Unopened)
    : path_(std::move(path)), subject_(std::move(subject)) {}

BoundedReader::BoundedReader(fs::path path, std::string subject)
    : BoundedReader(std::move(path), std::move(subject), Unopened{}) {
    if (const std::string problem = open(); !problem.empty())
        throw fileError(path_.string(), "cannot read: " + problem);
}

BoundedReader BoundedReader::dataFile(const fs::path& other) const {
    BoundedReader data(other, subject_, Unopened{});
    if (const std::string problem = data.open(); !problem.empty())
        throw fail("cannot read data file " + other.string() + ": " + problem);
    return data;
}

std::string BoundedReader::open() {
    std::error_code ec;
    size_ = fs::file_size(path_, ec);
    if (ec) return ec.message();
    in_.open(path_, std::ios::binary);
    if (!in_) return std::generic_category().message(errno);
    return {};
}

InputError BoundedReader::fail(const std::string& problem) const {
    return fileError(path_.string(), subject_ + ": " + printableText(problem, 400));
}

void BoundedReader::seek(std::uint64_t at, const std::string& what) {
    if (at > size_)
        throw fail(what + " at byte " + std::to_string(at) + ", beyond its " + std::to_string(size_) + " bytes");
    in_.rdbuf()->pubseekpos(std::streamoff(at));
    position_ = at;
}

void BoundedReader::require(std::uint64_t count, const std::string& what) const {
    if (count > remaining())
        throw fail(what + " of " + std::to_string(count) + " bytes, more than the " + std::to_string(remaining()) +
                   " bytes left");
}

void BoundedReader::skip(std::uint64_t count, const std::string& what) {
    require(count, what);
    seek(position_ + count, what);
}

std::string BoundedReader::bytes(std::size_t count, const std::string& what) {
    require(count, what);
    std::string text(count, '\0');
    bytes(text.data(), count, what);
    return text;
}

void BoundedReader::bytes(void* to, std::size_t count, const std::string& what) {
    require(count, what);
    if (readUpTo(to, count) < count) throw fail("it ends in " + what);
}

std::size_t BoundedReader::readUpTo(void* to, std::size_t count) {
    const std::size_t wanted = std::size_t(std::min<std::uint64_t>(count, remaining()));
    const std::size_t got = std::size_t(in_.rdbuf()->sgetn(static_cast<char*>(to), std::streamsize(wanted)));
    position_ += got;
    if (got < wanted) size_ = position_;  // the file shrank since it was opened: it ends here now
    return got;
}

std::string BoundedReader::bytesUpTo(std::size_t count) {
    std::string text(std::size_t(std::min<std::uint64_t>(count, remaining())), '\0');
    text.resize(readUpTo(text.data(), text.size()));
    return text;
}

int BoundedReader::next() {
    if (position_ == size_) return EOF;
    const int c = in_.rdbuf()->sbumpc();
    if (c == EOF)
        size_ = position_;  // as in readUpTo
    else
        ++position_;
    return c;
}

std::optional<std::string> BoundedReader::line() { return line(UINT64_MAX, {}); }

std::optional<std::string> BoundedReader::line(std::uint64_t limit, const std::string& beyondLimit) {
    if (position_ == size_) return std::nullopt;
    std::string text;
    for (int c; (c = next()) != EOF;) {
        if (position_ > limit) throw fail(beyondLimit);
        if (c == '\n') {
            lineEnded_ = true;
            return text;
        }
        text.push_back(char(c));
    }
    if (position_ >= limit) throw fail(beyondLimit);  // the file's end, counted as a line break, is past it
    lineEnded_ = false;
    return text;
}

std::uint64_t BoundedReader::countWords(std::uint64_t most) {
    std::uint64_t count = 0;
    bool inWord = false;
    for (int c; count < most && (c = next()) != EOF;) {
        // std::isspace in the C locale, as `stream >> word` splits words
        const bool space = c == ' ' || (c >= '\t' && c <= '\r');
        if (!space && !inWord) ++count;
        inWord = !space;
    }
    return count;
}

}  // namespace vr
