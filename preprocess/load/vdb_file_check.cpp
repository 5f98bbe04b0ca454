// OpenVDB file checks before openvdb::io::File reads it: OpenVDB allocates every length-prefixed string and metadata
// value at the length the file states (std::string(size, ' '): up to 4 GiB, zero-filled, for a 100-byte file; found
// by fuzz_vdb in GridDescriptor::read, MetaMap::readMeta and Transform::read). The header, the file's metadata, the
// grid descriptors and each grid's metadata and transform type are walked as OpenVDB reads them, each length
// checked against the bytes left. The trees are not: a length inside one is left to the allocator.
#include <array>
#include <cctype>
#include <cstdint>
#include <climits>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/header_checks.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// Reads the file as OpenVDB does, refusing any length beyond its end.
class VdbWalker {
public:
    explicit VdbWalker(const fs::path& path) : path_(path), in_(path, std::ios::binary) {
        if (!in_) throw fileError(path.string(), "cannot open");
        std::error_code ec;
        size_ = fs::file_size(path, ec);
        if (ec) throw fileError(path.string(), "cannot read: " + ec.message());
    }

    InputError fail(const std::string& problem) const {
        return fileError(path_.string(), "not a readable OpenVDB file: " + problem);
    }
    std::uint64_t left() { return size_ - std::min<std::uint64_t>(size_, std::uint64_t(in_.tellg())); }
    void seek(std::int64_t at, const char* what) {
        if (at < 0 || std::uint64_t(at) > size_)
            throw fail(std::string(what) + " at byte " + std::to_string(at) + ", beyond its " + std::to_string(size_) +
                       " bytes");
        in_.seekg(at);
    }
    template <typename T>
    T read(const char* what) {
        T value;
        if (!in_.read(reinterpret_cast<char*>(&value), sizeof value)) throw fail(std::string("it ends in ") + what);
        return value;
    }
    void require(std::uint64_t bytes, const std::string& what) {
        if (bytes > left())
            throw fail(what + " of " + std::to_string(bytes) + " bytes, more than the " + std::to_string(left()) +
                       " bytes left");
    }
    void skip(std::uint64_t bytes, const std::string& what) {
        require(bytes, what);
        in_.seekg(std::streamoff(bytes), std::ios::cur);
    }
    // openvdb::readString: a uint32 length and the characters.
    std::string string(const char* what) {
        const std::uint32_t length = read<std::uint32_t>(what);
        require(length, what);
        std::string text(length, '\0');
        in_.read(text.data(), length);
        return text;
    }

    // MetaMap::readMeta: a count, then name, type name and (Metadata::read) a uint32 size and the value. Fixed-size
    // types read their own size whatever the stated one; strings, unknown types and the delayed-load table (after
    // its own lengths are checked) take the stated size.
    void metadata(const char* where) {
        static const std::map<std::string, std::uint32_t> fixed{
            {"bool", 1},   {"int32", 4},  {"int64", 8},  {"float", 4},  {"double", 8}, {"vec2i", 8},
            {"vec2s", 8},  {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12}, {"vec3d", 24}, {"vec4i", 16},
            {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64}, {"mat4d", 128}};
        const std::uint32_t count = read<std::uint32_t>(where);
        for (std::uint32_t i = 0; i < count; ++i) {
            string(where);
            const std::string type = string(where);
            const std::uint32_t stated = read<std::uint32_t>(where);
            const std::string what = std::string(where) + " value of type \"" + type.substr(0, 40) + "\"";
            require(stated, what);
            const auto known = fixed.find(type);
            if (type == "__delayedload" && stated > 0) {
                const auto start = in_.tellg();
                delayedLoad(stated, where);
                in_.seekg(start);  // OpenVDB skips what it did not read, up to the stated size
            }
            skip(known != fixed.end() ? known->second : stated, what);
        }
    }

    // DelayedLoadMetadata::readValue: a count of leaf buffers, then a mask byte and a 64-bit size per buffer, each
    // array either blosc-compressed (a uint32 length and the bytes, allocated at that length) or raw (length 0, then
    // count values). The count is bounded by what the stated size could decompress to (at most 1032 to 1).
    void delayedLoad(std::uint32_t stated, const char* where) {
        const std::uint64_t count = read<std::uint32_t>(where);
        const std::string what = std::string(where) + ": delayed-load metadata";
        if (double(count) * 9 > double(stated) * 1032)
            throw fail(what + " for " + std::to_string(count) + " buffers in " + std::to_string(stated) + " bytes");
        const std::uint32_t maskBytes = read<std::uint32_t>(where);
        skip(maskBytes > 0 ? maskBytes : count, what);
        const std::uint32_t sizeBytes = read<std::uint32_t>(where);
        if (sizeBytes != UINT32_MAX) skip(sizeBytes > 0 ? sizeBytes : count * 8, what);
    }

    // Archive::readGrid up to the tree: the compression flags, the metadata and the transform's type name.
    void gridHead() {
        read<std::uint32_t>("a grid's compression flags");
        metadata("a grid's metadata");
        string("a grid's transform type");
    }

private:
    fs::path path_;
    std::ifstream in_;
    std::uint64_t size_ = 0;
};

}  // namespace

void checkVdbFile(const fs::path& path) {
    VdbWalker file(path);
    // Archive::readHeader, for the versions OpenVDB has written since 2014 (222: per-grid compression).
    if (file.read<std::int64_t>("the magic number") != 0x56444220) throw file.fail("no VDB magic number");
    const std::uint32_t version = file.read<std::uint32_t>("the file version");
    if (version < 222 || version > 224)
        throw file.fail("file format version " + std::to_string(version) + "; versions 222 to 224 are supported");
    file.read<std::uint32_t>("the library version");
    file.read<std::uint32_t>("the library version");
    const bool gridOffsets = file.read<char>("the header") != 0;
    std::array<char, 36> uuid;
    for (char& c : uuid) c = file.read<char>("the UUID");
    for (std::size_t i = 0; i < uuid.size(); ++i) {
        const bool hyphen = i == 8 || i == 13 || i == 18 || i == 23;
        if (hyphen ? uuid[i] != '-' : !std::isxdigit(static_cast<unsigned char>(uuid[i])))
            throw file.fail("a malformed UUID in the header");
    }
    file.metadata("the file's metadata");

    // File::open: the grid count and each GridDescriptor::read, followed by a seek to its end (or, in a stream
    // without grid offsets, by the grid itself).
    const std::int32_t grids = file.read<std::int32_t>("the grid count");
    if (grids < 0) throw file.fail("a grid count of " + std::to_string(grids));
    struct Place {
        std::int64_t grid, end;
    };
    std::vector<Place> places;
    for (std::int32_t g = 0; g < grids; ++g) {
        file.string("a grid name");
        file.string("a grid type");
        file.string("an instance parent name");
        const std::int64_t grid = file.read<std::int64_t>("a grid descriptor");
        file.read<std::int64_t>("a grid descriptor");  // where its buffers begin
        const std::int64_t end = file.read<std::int64_t>("a grid descriptor");
        if (!gridOffsets) {  // a stream: the first grid follows its descriptor, and its tree is not walked here
            file.gridHead();
            return;
        }
        places.push_back({grid, end});
        file.seek(end, "a grid ending");
    }
    // Each grid's head, where OpenVDB seeks to read it.
    for (const Place& p : places) {
        file.seek(p.grid, "a grid");
        file.gridHead();
    }
}

}  // namespace vr
