// OpenVDB file checks before openvdb::io::File reads it: OpenVDB allocates every length-prefixed string and metadata
// value at the length the file states (std::string(size, ' '): up to 4 GiB, zero-filled, for a 100-byte file; found
// by fuzz_vdb in GridDescriptor::read, MetaMap::readMeta and Transform::read), and trusts the trees as much: OpenVDB
// 10 reads an uncompressed chunk of any stated length into a node's fixed buffer (io::unzipFromStream: a heap
// overflow), allocates a zipped chunk's stated length, and loops over a root's stated tile count whatever the file
// holds (all found by fuzz_vdb). The header, the metadata, the grid descriptors, each grid's transform and every
// float grid's tree (the only trees the loader lets OpenVDB read) are walked as OpenVDB 10 reads them, each length
// and count checked against the bytes left and each node's values against what the node holds.
#include <openvdb/io/Compression.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <climits>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "preprocess/load/bounded_reader.h"
#include "preprocess/load/header_checks.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// What a blosc chunk of `length` bytes decompresses to, from its 16-byte header (versions, flags and type size, then
// uint32s: the decompressed size, the block size and the compressed size), or UINT64_MAX where the header does not
// fit the chunk: shorter than a header, or stating another compressed size, by which blosc 1 bounds its reads.
std::uint64_t bloscSize(const unsigned char* chunk, std::uint64_t length) {
    std::uint32_t nbytes, cbytes;
    if (length < 16) return UINT64_MAX;
    std::memcpy(&nbytes, chunk + 4, 4);
    std::memcpy(&cbytes, chunk + 12, 4);
    return cbytes == length ? nbytes : UINT64_MAX;
}

// openvdb::readString: a uint32 length and the characters.
std::string readString(BoundedReader& file, const std::string& what) {
    const std::uint32_t length = file.littleEndian<std::uint32_t>(what);
    return file.bytes(length, what);
}

// Where OpenVDB seeks to an offset the file states.
void seekTo(BoundedReader& file, std::int64_t at, const char* what) {
    if (at < 0) throw file.fail(std::string(what) + " at byte " + std::to_string(at) + ", before its start");
    file.seek(std::uint64_t(at), what);
}

void readDelayedLoad(BoundedReader& file, std::uint32_t stated, const char* where);

// MetaMap::readMeta: a count, then name, type name and (Metadata::read) a uint32 size and the value. Fixed-size
// types read their own size whatever the stated one; strings, unknown types and the delayed-load table (after
// its own lengths are checked) take the stated size. Returns "is_saved_as_half_float" (the last of that name,
// GridBase::saveFloatAsHalf), which says whether a grid's tree holds half floats; OpenVDB writes it as a bool.
bool readMetadata(BoundedReader& file, const char* where) {
    static const std::map<std::string, std::uint32_t> fixed{
        {"bool", 1},   {"int32", 4},  {"int64", 8},  {"float", 4},  {"double", 8}, {"vec2i", 8},
        {"vec2s", 8},  {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12}, {"vec3d", 24}, {"vec4i", 16},
        {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64}, {"mat4d", 128}};
    bool half = false;
    const std::uint32_t count = file.littleEndian<std::uint32_t>(where);
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::string name = readString(file, where);
        const std::string type = readString(file, where);
        const std::uint32_t stated = file.littleEndian<std::uint32_t>(where);
        const std::string what = std::string(where) + " value of type \"" + type.substr(0, 40) + "\"";
        file.require(stated, what);
        const auto known = fixed.find(type);
        if (name == "is_saved_as_half_float") {
            const char value = type == "bool" ? file.littleEndian<char>(what) : char(2);
            if (value != 0 && value != 1) throw file.fail(std::string(where) + ": is_saved_as_half_float not a bool");
            half = value;
            continue;
        }
        if (type == "__delayedload" && stated > 0) {
            readDelayedLoad(file, stated, where);
            continue;
        }
        file.skip(known != fixed.end() ? known->second : stated, what);
    }
    return half;
}

// DelayedLoadMetadata::readValue: a count of leaf buffers, then a mask byte per buffer and (unless its length is
// UINT32_MAX) a 64-bit size per buffer, each array either blosc-compressed (a uint32 length and the bytes, which
// OpenVDB allocates at that length and at the size their header states) or raw (length 0, then the values). What
// is left of the stated size is read and discarded, but longer arrays are read past it. The count is bounded by
// what the stated size could decompress to (at most 1032 to 1).
void readDelayedLoad(BoundedReader& file, std::uint32_t stated, const char* where) {
    const std::uint64_t start = file.position();
    const std::uint64_t count = file.littleEndian<std::uint32_t>(where);
    const std::string what = std::string(where) + ": delayed-load metadata";
    if (double(count) * 9 > double(stated) * 1032)
        throw file.fail(what + " for " + std::to_string(count) + " buffers in " + std::to_string(stated) + " bytes");
    const auto array = [&](std::uint32_t length, std::uint64_t size) {
        if (length == 0) return file.skip(size, what);
        file.require(length, what);
        std::array<unsigned char, 16> header{};
        const std::uint32_t headerBytes = std::min<std::uint32_t>(length, header.size());
        file.bytes(header.data(), headerBytes, what);
        const std::uint64_t unpacked = bloscSize(header.data(), length);
        // compression::bloscCompress pads what is shorter to 128 bytes
        if (unpacked != size && !(size < 128 && unpacked == 128))
            throw file.fail(what + ": a blosc array of " + std::to_string(length) + " bytes that is not " +
                            std::to_string(size) + " bytes compressed");
        file.skip(length - headerBytes, what);
    };
    array(file.littleEndian<std::uint32_t>(where), count);
    if (const std::uint32_t length = file.littleEndian<std::uint32_t>(where); length != UINT32_MAX)
        array(length, count * 8);
    const std::uint64_t consumed = file.position() - start;
    if (consumed < stated) file.skip(stated - consumed, what);
}

// Transform::read: the map's type name, then the map (math/Maps.h): its Vec3d and Mat4d members; a frustum's
// bounding box, taper and depth are followed by a second map.
void readTransform(BoundedReader& file, const char* what) {
    static const std::map<std::string, std::uint32_t> sizes{
        {"AffineMap", 128},          {"UnitaryMap", 128},
        {"ScaleMap", 120},           {"UniformScaleMap", 120},
        {"TranslationMap", 24},      {"ScaleTranslateMap", 144},
        {"NonlinearFrustumMap", 64}, {"UniformScaleTranslateMap", 144}};
    const std::string type = readString(file, what);
    const auto map = sizes.find(type);
    if (map == sizes.end()) throw file.fail(std::string(what) + " of unknown type \"" + type.substr(0, 40) + "\"");
    file.skip(map->second, what);
    if (type == "NonlinearFrustumMap") readTransform(file, what);
}

// Archive::readGrid up to the tree: the compression flags, the metadata and the transform.
struct GridHead {
    std::uint32_t compression;
    bool half;
};
GridHead readGridHead(BoundedReader& file) {
    GridHead head;
    head.compression = file.littleEndian<std::uint32_t>("a grid's compression flags");
    head.half = readMetadata(file, "a grid's metadata");
    readTransform(file, "a grid's transform");
    return head;
}

// A float grid's tree (Tree<RootNode<InternalNode<InternalNode<LeafNode<float, 3>, 4>, 5>>>), walked as OpenVDB 10
// reads it: Tree::readTopology, then Tree::readBuffers.
class FloatTreeWalk {
public:
    FloatTreeWalk(BoundedReader& file, const GridHead& head, const std::string& grid)
        : file_(file), head_(head), grid_("float grid \"" + grid.substr(0, 40) + "\": ") {}

    void topology() {
        file_.littleEndian<std::int32_t>(grid_ + "the tree's buffer count");
        file_.littleEndian<float>(grid_ + "the background");
        // RootNode::readTopology: tiles (origin, value, active byte), then children (origin, topology), each kept
        // in a map by origin, which orders the buffers.
        const std::uint32_t tiles = file_.littleEndian<std::uint32_t>(grid_ + "the root's tile count");
        const std::uint32_t children = file_.littleEndian<std::uint32_t>(grid_ + "the root's child count");
        file_.require(std::uint64_t(tiles) * 17, grid_ + std::to_string(tiles) + " root tiles");
        for (std::uint32_t i = 0; i < tiles; ++i) {
            origin("a root tile");
            file_.skip(5, grid_ + "a root tile");
        }
        for (std::uint32_t i = 0; i < children; ++i) internalTopology(5, children_[origin("a root child")]);
    }

    // RootNode::readBuffers: each child's in the order of origins, and (InternalNode::readBuffers) each of its
    // leaves' in index order, as in the topology. LeafNode::readBuffers reads (or skips) the value mask again: it
    // must be the topology's, so that either way the same values are read.
    void buffers() {
        for (const auto& [origin, leaves] : children_) {
            for (const LeafMask& mask : leaves) {
                if (leafMask() != mask) throw file_.fail(grid_ + "a leaf's value mask differs from its topology's");
                values(512, ones(mask), "a leaf");
            }
        }
    }

private:
    using Origin = std::array<std::int32_t, 3>;  // compared as openvdb::Coord: x, then y, then z
    using LeafMask = std::array<std::uint64_t, 8>;

    // A root entry's origin: OpenVDB's root table keys are multiples of a child's extent (4096), one entry each.
    Origin origin(const char* what) {
        Origin o;
        for (std::int32_t& c : o) c = file_.littleEndian<std::int32_t>(grid_ + what);
        const auto at = [&] {
            return " at (" + std::to_string(o[0]) + ", " + std::to_string(o[1]) + ", " + std::to_string(o[2]) + ")";
        };
        if ((o[0] | o[1] | o[2]) & 4095) throw file_.fail(grid_ + what + at() + ", off the root's 4096 grid");
        if (!seen_.insert(o).second) throw file_.fail(grid_ + "two root entries" + at());
        return o;
    }

    static std::uint32_t ones(std::span<const std::uint64_t> mask) {
        std::uint32_t n = 0;
        for (std::uint64_t w : mask) n += std::popcount(w);
        return n;
    }
    LeafMask leafMask() {
        LeafMask mask;
        file_.bytes(mask.data(), sizeof mask, grid_ + "a leaf's value mask");
        return mask;
    }

    // InternalNode<_, Log2Dim>::readTopology: the child and value masks, all its values (readCompressedValues),
    // then each child's topology in index order (LeafNode::readTopology: its value mask).
    void internalTopology(int log2Dim, std::vector<LeafMask>& leaves) {
        std::vector<std::uint64_t> childMask(std::size_t(1) << (3 * log2Dim - 6)), valueMask(childMask.size());
        file_.bytes(childMask.data(), childMask.size() * 8, grid_ + "an internal node's child mask");
        file_.bytes(valueMask.data(), valueMask.size() * 8, grid_ + "an internal node's value mask");
        values(std::uint32_t(childMask.size() * 64), ones(valueMask), "an internal node");
        for (std::uint64_t w : childMask) {
            for (; w; w &= w - 1) {
                if (log2Dim == 5)
                    internalTopology(4, leaves);
                else
                    leaves.push_back(leafMask());
            }
        }
    }

    // io::readCompressedValues: a byte saying which inactive values are stored (io::NO_MASK_OR_INACTIVE_VALS ...),
    // those values and a selection mask, then the node's values, all or (COMPRESS_ACTIVE_MASK) only the active
    // ones, as floats or half floats (none at all for no half floats), zipped, blosc-compressed or raw.
    void values(std::uint32_t size, std::uint32_t active, const char* node) {
        using namespace openvdb::io;
        const std::string what = grid_ + node + "'s values";
        const std::int8_t stored = file_.littleEndian<std::int8_t>(what);
        if (stored < NO_MASK_OR_INACTIVE_VALS || stored > NO_MASK_AND_ALL_VALS)
            throw file_.fail(what + ": an unknown inactive-value code " + std::to_string(stored));
        if (stored == NO_MASK_AND_ONE_INACTIVE_VAL || stored == MASK_AND_ONE_INACTIVE_VAL)
            file_.skip(sizeof(float), what);
        if (stored == MASK_AND_TWO_INACTIVE_VALS) file_.skip(2 * sizeof(float), what);
        if (stored >= MASK_AND_NO_INACTIVE_VALS && stored <= MASK_AND_TWO_INACTIVE_VALS) file_.skip(size / 8, what);

        const std::uint64_t count =
            (head_.compression & COMPRESS_ACTIVE_MASK) && stored != NO_MASK_AND_ALL_VALS ? active : size;
        if (head_.half && count == 0) return;  // HalfReader reads nothing
        const std::uint64_t bytes = count * (head_.half ? 2 : sizeof(float));
        if (head_.compression & COMPRESS_BLOSC)
            chunk(bytes, true, what);
        else if (head_.compression & COMPRESS_ZIP)
            chunk(bytes, false, what);
        else
            file_.skip(bytes, what);
    }

    // io::unzipFromStream, io::bloscFromStream: an int64 length, negative for that many raw bytes, which OpenVDB 10
    // reads into the node's buffer whatever their number, else the compressed bytes, allocated at that length.
    void chunk(std::uint64_t bytes, bool blosc, const std::string& what) {
        const std::int64_t stated = file_.littleEndian<std::int64_t>(what);
        const std::string held = " where the node holds " + std::to_string(bytes);
        if (stated <= 0) {
            const std::uint64_t raw = 0 - std::uint64_t(stated);
            if (raw != bytes) throw file_.fail(what + ": " + std::to_string(raw) + " uncompressed bytes" + held);
            file_.skip(raw, what);
            return;
        }
        std::vector<unsigned char> packed;
        file_.require(std::uint64_t(stated), what + (blosc ? ", blosc-compressed," : ", zipped,"));
        packed.resize(std::size_t(stated));
        file_.bytes(packed.data(), packed.size(), what);
        const std::uint64_t unpacked =
            blosc ? bloscSize(packed.data(), packed.size()) : unzippedSize(packed, bytes);
        if (unpacked != bytes)
            throw file_.fail(what + (blosc ? " decompress (blosc) to " : " decompress (zlib) to ") +
                             (unpacked == UINT64_MAX ? "nothing (corrupt)" : std::to_string(unpacked) + " bytes") +
                             held);
    }

    // What zlib inflates a chunk to (UINT64_MAX: corrupt, or more than the node holds).
    static std::uint64_t unzippedSize(const std::vector<unsigned char>& packed, std::uint64_t bytes) {
        std::vector<Bytef> out(bytes + 1);
        uLongf outLength = uLongf(out.size());
        uLong inLength = uLong(packed.size());
        return uncompress2(out.data(), &outLength, packed.data(), &inLength) == Z_OK ? outLength : UINT64_MAX;
    }

    BoundedReader& file_;
    GridHead head_;
    std::string grid_;
    std::set<Origin> seen_;
    std::map<Origin, std::vector<LeafMask>> children_;  // each root child's leaves' value masks
};

struct Descriptor {
    std::string name, type, parent;
    std::int64_t grid;
};

// openvdb::FloatGrid's type name, with the suffix of a grid saved as half floats.
bool isFloatGrid(const std::string& type) { return type == "Tree_float_5_4_3" || type == "Tree_float_5_4_3_HalfFloat"; }

// A grid name without GridDescriptor's unique-name suffix ("\x1eN", or "[N]" as io::File looks names up).
std::string baseName(std::string name) {
    name = name.substr(0, name.find('\x1e'));
    const std::size_t open = name.rfind('[');
    if (open != std::string::npos && name.back() == ']' && name.size() > open + 2 &&
        name.find_first_not_of("0123456789", open + 1) == name.size() - 1)
        name.resize(open);
    return name;
}

// Walks a float grid's tree, whose head was just read.
void walkFloatTree(BoundedReader& file, const GridHead& head, const std::string& name) {
    FloatTreeWalk tree(file, head, name);
    tree.topology();
    tree.buffers();
}

}  // namespace

void checkVdbFile(const fs::path& path) {
    BoundedReader file(path, "not a readable OpenVDB file");
    // Archive::readHeader, for the versions OpenVDB has written since 2014 (222: per-grid compression).
    if (file.littleEndian<std::int64_t>("the magic number") != 0x56444220) throw file.fail("no VDB magic number");
    const std::uint32_t version = file.littleEndian<std::uint32_t>("the file version");
    if (version < 222 || version > 224)
        throw file.fail("file format version " + std::to_string(version) + "; versions 222 to 224 are supported");
    file.littleEndian<std::uint32_t>("the library version");
    file.littleEndian<std::uint32_t>("the library version");
    const bool gridOffsets = file.littleEndian<char>("the header") != 0;
    const std::string uuid = file.bytes(36, "the UUID");
    for (std::size_t i = 0; i < uuid.size(); ++i) {
        const bool hyphen = i == 8 || i == 13 || i == 18 || i == 23;
        if (hyphen ? uuid[i] != '-' : !std::isxdigit(static_cast<unsigned char>(uuid[i])))
            throw file.fail("a malformed UUID in the header");
    }
    readMetadata(file, "the file's metadata");

    // File::open: the grid count and each GridDescriptor::read, followed by a seek to its end (or, in a stream
    // without grid offsets, by the grid itself, all of which io::File reads).
    const std::int32_t grids = file.littleEndian<std::int32_t>("the grid count");
    if (grids < 0) throw file.fail("a grid count of " + std::to_string(grids));
    std::vector<Descriptor> descriptors;
    for (std::int32_t g = 0; g < grids; ++g) {
        Descriptor d;
        d.name = readString(file, "a grid name");
        d.type = readString(file, "a grid type");
        d.parent = readString(file, "an instance parent name");
        d.grid = file.littleEndian<std::int64_t>("a grid descriptor");
        file.littleEndian<std::int64_t>("a grid descriptor");  // where its buffers begin
        const std::int64_t end = file.littleEndian<std::int64_t>("a grid descriptor");
        if (!gridOffsets) {
            const GridHead head = readGridHead(file);
            if (!d.parent.empty()) continue;  // an instance: no tree of its own
            if (!isFloatGrid(d.type))
                throw file.fail("a stream without grid offsets holding a tree of type \"" + d.type.substr(0, 40) +
                                "\", which would be read but cannot be checked");
            walkFloatTree(file, head, d.name);
            continue;
        }
        descriptors.push_back(d);
        seekTo(file, end, "a grid ending");
    }
    // Each grid where OpenVDB seeks to read it: every head, and the trees of float grids. A float grid that is an
    // instance gets its parent's tree, found by name: every grid that name could find must be a float grid.
    for (const Descriptor& d : descriptors) {
        seekTo(file, d.grid, "a grid");
        const GridHead head = readGridHead(file);
        if (!isFloatGrid(d.type)) continue;
        if (d.parent.empty()) {
            walkFloatTree(file, head, d.name);
            continue;
        }
        for (const Descriptor& parent : descriptors)
            if (baseName(parent.name) == baseName(d.parent) && !isFloatGrid(parent.type))
                throw file.fail("float grid \"" + d.name.substr(0, 40) + "\" instancing the tree of a grid of type \"" +
                                parent.type.substr(0, 40) + "\"");
    }
}

}  // namespace vr
