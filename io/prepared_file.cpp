#include "io/prepared_file.h"

#include <fcntl.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>

#include "io/atomic_file.h"
#include "io/crc32.h"
#include "io/ray_probe_json.h"
#include "core/errors.h"
#include "core/extent_code.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;

// Chunks are stored as the in-memory arrays, so the file is little-endian only where the machine is.
static_assert(std::endian::native == std::endian::little, "the prepared format is little-endian");

namespace {

constexpr char kMagic[8] = {'V', 'O', 'L', 'P', 'R', 'E', 'P', '\0'};
constexpr std::size_t kPreambleBytes = sizeof(kMagic) + sizeof(uint32_t) + sizeof(uint64_t);
// Limits that catch a corrupted header before it turns into a huge allocation.
constexpr uint64_t kMaxHeaderBytes = uint64_t(1) << 30;
constexpr int kMaxDim = 1 << 16;
constexpr std::size_t kMaxVoxels = std::size_t(1) << 36;

// What a chunk of a given name must hold: its element type and components per voxel.
struct ChunkLayout {
    const char* type;
    int components;
    std::size_t elementBytes;
};

ChunkLayout layoutOf(const std::string& name, ExtentCode eacdCode) {
    if (name == "sigma") return {"float32", 1, 4};
    if (name == "colour" || name == "normal") return {"float32", 3, 4};
    if (name == "labels") return {"uint32", 1, 4};
    if (name == "pc") return {"uint8", 1, 1};
    for (int o = 0; o < kOctants; ++o) {
        if (name == "acd" + std::to_string(o)) return {"uint8", 1, 1};
        if (name == "eacd" + std::to_string(o))
            return eacdCode == ExtentCode::Exact ? ChunkLayout{"uint8", 3, 1}
                   : eacdCode == ExtentCode::Log16 ? ChunkLayout{"uint16", 1, 2}
                                                   : ChunkLayout{"uint8", 1, 1};
    }
    return {nullptr, 0, 0};
}

// One array of the PreparedVolume, as bytes, on its way into the file.
struct ChunkSource {
    std::string name;
    const void* data;
    std::size_t elements;  // voxels present (0: chunk absent)
};

template <typename T>
ChunkSource source(std::string name, const std::vector<T>& v) {
    return {std::move(name), v.data(), v.size()};
}

std::vector<ChunkSource> chunkSources(const PreparedVolume& p) {
    std::vector<ChunkSource> all = {source("sigma", p.classified.sigma), source("colour", p.classified.colour),
                                    source("normal", p.classified.normal), source("labels", p.regions.label),
                                    source("pc", p.fields.pc)};
    for (int o = 0; o < kOctants; ++o) all.push_back(source("acd" + std::to_string(o), p.fields.acd[o]));
    for (int o = 0; o < kOctants; ++o)
        all.push_back({"eacd" + std::to_string(o), p.fields.eacd[o].data(), p.fields.eacd[o].size()});
    std::erase_if(all, [](const ChunkSource& c) { return c.elements == 0; });
    return all;
}

json vec3Json(const Vec3d& v) { return json::array({v.x, v.y, v.z}); }

// The ray probe is stored among the statistics (their form predates its type).
json statisticsJson(const PreparedMetadata& m) {
    json s = m.statistics.is_null() ? json::object() : m.statistics;
    if (m.rayProbe) s["rayProbe"] = rayProbeJson(*m.rayProbe);
    return s;
}

json metadataJson(const PreparedMetadata& m) {
    return {{"source", m.source},
            {"classification", m.classification},
            {"opacityThreshold", m.segmentation.opacityThreshold},
            {"angleThresholdDeg", m.segmentation.angleThresholdDeg},
            {"useNormals", m.segmentation.useNormals},
            {"trilinear", m.segmentation.trilinear},
            {"distanceCap", m.distanceCap},
            {"statistics", statisticsJson(m)}};
}

void checkSizes(const fs::path& path, const PreparedVolume& p) {
    const GridGeometry& g = p.classified.grid;
    auto fail = [&](const std::string& what) { return fileError(path.string(), "cannot write: " + what); };
    if (g.dims.x < 1 || g.dims.y < 1 || g.dims.z < 1) throw fail("empty grid");
    if (p.regions.dims != g.dims) throw fail("region labels and classified volume have different dims");
    bool anyField = p.fields.hasPC() || p.fields.hasACD() || p.fields.hasEACD();
    if (anyField && p.fields.dims != g.dims) throw fail("distance fields and classified volume have different dims");
    if (p.classified.sigma.size() != g.voxels() || p.classified.colour.size() != g.voxels() ||
        p.regions.label.size() != g.voxels())
        throw fail("sigma, colour and labels must hold one value per voxel");
    for (const ChunkSource& c : chunkSources(p))
        if (c.elements != g.voxels()) throw fail("chunk '" + c.name + "' does not hold one value per voxel");
    for (int o = 1; o < kOctants; ++o)
        if (p.fields.acd[o].empty() != p.fields.acd[0].empty() || p.fields.eacd[o].empty() != p.fields.eacd[0].empty())
            throw fail("ACD and EACD need all 8 octants or none");
    for (const ExtentField& octant : p.fields.eacd)
        if (octant.code() != p.fields.eacdCode()) throw fail("the EACD octants are in different codes");
}

// Reading: every problem becomes an InputError naming the file. pread() lets chunks be read from many threads.
class Reader {
public:
    explicit Reader(const fs::path& path) : path_(path) {
        std::error_code ec;
        if (!fs::exists(path, ec)) throw fail("no such file");
        if (!fs::is_regular_file(path, ec)) throw fail("not a regular file");
        size_ = fs::file_size(path, ec);
        if (ec) throw fail("cannot read: " + ec.message());
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) throw fail(std::string("cannot open: ") + std::strerror(errno));
    }
    ~Reader() { ::close(fd_); }
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;

    InputError fail(const std::string& problem) const { return fileError(path_.string(), problem); }
    uint64_t size() const { return size_; }

    void read(uint64_t offset, void* to, std::size_t bytes, const std::string& what) const {
        if (offset + bytes > size_) throw fail("truncated " + what + " (file ends at byte " + std::to_string(size_) + ")");
        auto* p = static_cast<char*>(to);
        while (bytes > 0) {
            ssize_t got = ::pread(fd_, p, bytes, off_t(offset));
            if (got < 0 && errno == EINTR) continue;
            if (got <= 0) throw fail("cannot read " + what + (got < 0 ? std::string(": ") + std::strerror(errno) : ""));
            p += got;
            offset += uint64_t(got);
            bytes -= std::size_t(got);
        }
    }

private:
    fs::path path_;
    uint64_t size_ = 0;
    int fd_ = -1;
};

struct ChunkEntry {
    uint64_t offset, bytes;
    uint32_t crc;
};

// Pulls a typed value out of the header; a missing key or a wrong type is a bad header, not a crash.
template <typename T>
T field(const Reader& r, const json& j, const char* key) {
    try {
        return j.at(key).get<T>();
    } catch (const json::exception&) {
        throw r.fail(std::string("bad header: missing or invalid '") + key + "'");
    }
}

// A non-negative integer no larger than `max` (a float or an out-of-range number would not convert safely).
uint64_t countField(const Reader& r, const json& j, const char* key, uint64_t max) {
    json v = field<json>(r, j, key);
    if (!v.is_number_unsigned() || v.get<uint64_t>() > max)
        throw r.fail(std::string("bad header: '") + key + "' must be an integer from 0 to " + std::to_string(max));
    return v.get<uint64_t>();
}

Vec3d vec3Field(const Reader& r, const json& j, const char* key) {
    auto v = field<std::vector<double>>(r, j, key);
    if (v.size() != 3) throw r.fail(std::string("bad header: '") + key + "' needs 3 numbers");
    return {v[0], v[1], v[2]};
}

// One chunk to read: where it is, and how to size its destination array and get at its bytes.
struct ChunkRead {
    std::string name;
    ChunkEntry entry;
    std::function<char*()> allocate;
};

template <typename T>
std::function<char*()> destination(std::vector<T>& vec, std::size_t bytes, ExtentCode) {
    return [&vec, bytes] {
        vec.resize(bytes / sizeof(T));
        return reinterpret_cast<char*>(vec.data());
    };
}
std::function<char*()> destination(ExtentField& field, std::size_t bytes, ExtentCode code) {
    return [&field, bytes, code] {
        field = ExtentField(code, bytes / extentCodeBytes(code));
        return reinterpret_cast<char*>(field.data());
    };
}

// Allocates every destination (in parallel: the page faults are a large part of the cost), then reads and
// checksums the blocks of all chunks in parallel (each block while it is still in cache), and compares each
// chunk's combined CRC-32.
void readChunks(const Reader& r, uint64_t dataStart, const std::vector<ChunkRead>& reads) {
    std::vector<char*> data(reads.size());
    tbb::parallel_for(std::size_t(0), reads.size(), [&](std::size_t i) { data[i] = reads[i].allocate(); });

    struct Block {
        std::size_t chunk;
        uint64_t begin, bytes;
    };
    std::vector<Block> blocks;
    for (std::size_t i = 0; i < reads.size(); ++i)
        for (uint64_t b = 0; b < reads[i].entry.bytes; b += kCrcBlock)
            blocks.push_back({i, b, std::min<uint64_t>(kCrcBlock, reads[i].entry.bytes - b)});
    std::vector<uint32_t> crcs(blocks.size());
    tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t k) {
        const Block& b = blocks[k];
        const ChunkRead& c = reads[b.chunk];
        char* to = data[b.chunk] + b.begin;
        r.read(dataStart + c.entry.offset + b.begin, to, b.bytes, "chunk '" + c.name + "'");
        crcs[k] = crc32Of(to, b.bytes);
    });

    std::vector<uint32_t> chunkCrc(reads.size(), 0);
    for (std::size_t k = 0; k < blocks.size(); ++k)
        chunkCrc[blocks[k].chunk] = crc32Combine(chunkCrc[blocks[k].chunk], crcs[k], blocks[k].bytes);
    for (std::size_t i = 0; i < reads.size(); ++i)
        if (chunkCrc[i] != reads[i].entry.crc)
            throw r.fail("chunk '" + reads[i].name + "' checksum mismatch (file is corrupted)");
}

}  // namespace

void writePrepared(const fs::path& path, const PreparedVolume& p) {
    checkSizes(path, p);
    const GridGeometry& g = p.classified.grid;
    const ExtentCode code = p.fields.eacdCode();
    std::vector<ChunkSource> chunks = chunkSources(p);

    json table = json::array();
    uint64_t offset = 0;
    for (const ChunkSource& c : chunks) {
        ChunkLayout l = layoutOf(c.name, code);
        uint64_t bytes = uint64_t(c.elements) * l.components * l.elementBytes;
        table.push_back({{"name", c.name},
                         {"type", l.type},
                         {"components", l.components},
                         {"offset", offset},
                         {"bytes", bytes},
                         {"crc32", crc32Of(c.data, bytes)}});
        offset += bytes;
    }
    json header = {{"grid",
                    {{"dims", {g.dims.x, g.dims.y, g.dims.z}}, {"spacing", vec3Json(g.spacing)}, {"origin", vec3Json(g.origin)}}},
                   {"referenceStep", p.classified.referenceStep},
                   {"regionCount", p.regions.count},
                   {"metadata", metadataJson(p.meta)},
                   {"eacdCode", extentCodeName(code)},
                   {"chunks", table}};
    // Paths need not be UTF-8: replace what JSON cannot hold rather than fail the write.
    std::string text = header.dump(1, ' ', false, json::error_handler_t::replace);

    writeFileAtomically(path, [&](std::ostream& out) {
        uint32_t version = kPreparedFormatVersion;
        uint64_t headerBytes = text.size();
        uint32_t headerCrc = crc32Of(text.data(), text.size());
        out.write(kMagic, sizeof(kMagic));
        out.write(reinterpret_cast<const char*>(&version), sizeof(version));
        out.write(reinterpret_cast<const char*>(&headerBytes), sizeof(headerBytes));
        out.write(text.data(), std::streamsize(text.size()));
        out.write(reinterpret_cast<const char*>(&headerCrc), sizeof(headerCrc));
        for (std::size_t i = 0; i < chunks.size(); ++i)
            out.write(static_cast<const char*>(chunks[i].data), std::streamsize(table[i]["bytes"].get<uint64_t>()));
    });
}

namespace {

// Everything the header says, checked against the file: all of the prepared volume but the chunks' contents.
struct Header {
    PreparedVolume prepared;  // grid, reference step, region count and metadata
    ExtentCode eacdCode = kDefaultExtentCode;
    std::map<std::string, ChunkEntry> chunks;  // by name
    uint64_t dataStart = 0;                    // where the chunks' offsets start
};

Header readHeader(const Reader& r) {
    Header h;
    char magic[sizeof(kMagic)];
    if (r.size() < kPreambleBytes)
        throw r.fail("not a prepared file (only " + std::to_string(r.size()) + " bytes; run volprep to make one)");
    r.read(0, magic, sizeof(magic), "magic");
    if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
        throw r.fail("not a prepared file (no VOLPREP magic; run volprep to make one)");
    uint32_t version = 0;
    r.read(8, &version, sizeof(version), "version");
    if (version != uint32_t(kPreparedFormatVersion))
        throw r.fail("prepared format version " + std::to_string(version) + ", this build reads version " +
                     std::to_string(kPreparedFormatVersion) + " (run volprep again)");
    uint64_t headerBytes = 0;
    r.read(12, &headerBytes, sizeof(headerBytes), "header length");
    if (headerBytes > kMaxHeaderBytes) throw r.fail("bad header length " + std::to_string(headerBytes));
    std::string text(headerBytes, '\0');
    r.read(kPreambleBytes, text.data(), headerBytes, "header");
    uint32_t headerCrc = 0;
    r.read(kPreambleBytes + headerBytes, &headerCrc, sizeof(headerCrc), "header");
    if (headerCrc != crc32Of(text.data(), text.size())) throw r.fail("header checksum mismatch (file is corrupted)");
    const uint64_t dataStart = h.dataStart = kPreambleBytes + headerBytes + sizeof(headerCrc);

    json header;
    try {
        header = json::parse(text);
    } catch (const json::exception& e) {
        throw r.fail(std::string("bad header: ") + e.what());
    }

    PreparedVolume& p = h.prepared;
    json grid = field<json>(r, header, "grid");
    json dims = field<json>(r, grid, "dims");
    if (!dims.is_array() || dims.size() != 3) throw r.fail("bad header: 'dims' needs 3 numbers");
    std::string dimsText = dims[0].dump() + "x" + dims[1].dump() + "x" + dims[2].dump();
    for (const json& d : dims)
        if (!d.is_number_unsigned() || d.get<uint64_t>() < 1 || d.get<uint64_t>() > kMaxDim)
            throw r.fail("absurd grid dims " + dimsText);
    Vec3i n{dims[0].get<int>(), dims[1].get<int>(), dims[2].get<int>()};
    if (voxelCount(n) > kMaxVoxels) throw r.fail("absurd grid dims " + dimsText + " (too many voxels)");
    GridGeometry& g = p.classified.grid;
    g.dims = n;
    g.spacing = vec3Field(r, grid, "spacing");
    g.origin = vec3Field(r, grid, "origin");
    // A zero, negative or overflowing spacing makes every ray degenerate (a zero step never ends).
    for (int a = 0; a < 3; ++a)
        if (!(g.spacing[a] > 0) || !std::isfinite(g.origin[a]))
            throw r.fail("bad header: 'spacing' must be positive and 'origin' finite");
    if (!std::isfinite(length(g.extent()))) throw r.fail("bad header: 'spacing' x dims overflows (extent not finite)");
    p.classified.referenceStep = field<double>(r, header, "referenceStep");
    p.regions.dims = n;
    p.regions.count = uint32_t(countField(r, header, "regionCount", UINT32_MAX));

    json meta = field<json>(r, header, "metadata");
    p.meta.source = field<std::string>(r, meta, "source");
    p.meta.classification = field<std::string>(r, meta, "classification");
    p.meta.segmentation.opacityThreshold = field<double>(r, meta, "opacityThreshold");
    p.meta.segmentation.angleThresholdDeg = field<double>(r, meta, "angleThresholdDeg");
    p.meta.segmentation.useNormals = field<bool>(r, meta, "useNormals");
    p.meta.segmentation.trilinear = field<bool>(r, meta, "trilinear");
    p.meta.distanceCap = int(countField(r, meta, "distanceCap", kDistanceCap));
    p.meta.statistics = field<json>(r, meta, "statistics");
    if (p.meta.statistics.contains("rayProbe")) {
        p.meta.rayProbe = rayProbeFromJson(p.meta.statistics["rayProbe"]);
        p.meta.statistics.erase("rayProbe");
    }
    ExtentCode& eacdCode = h.eacdCode;
    try {
        eacdCode = parseExtentCode(field<std::string>(r, header, "eacdCode"), "'eacdCode'");
    } catch (const InputError& e) {
        throw r.fail(std::string("bad header: ") + e.what());
    }

    // The chunk table must agree with the dims and lie inside the file before anything is allocated.
    std::map<std::string, ChunkEntry>& table = h.chunks;
    for (const json& c : field<json>(r, header, "chunks")) {
        auto name = field<std::string>(r, c, "name");
        ChunkLayout l = layoutOf(name, eacdCode);
        if (!l.type) throw r.fail("bad header: unknown chunk '" + name + "'");
        if (table.count(name)) throw r.fail("bad header: chunk '" + name + "' appears twice");
        if (field<std::string>(r, c, "type") != l.type || countField(r, c, "components", 3) != uint64_t(l.components))
            throw r.fail("bad header: chunk '" + name + "' should be " + std::to_string(l.components) + " x " + l.type);
        ChunkEntry e{countField(r, c, "offset", UINT64_MAX), countField(r, c, "bytes", UINT64_MAX),
                     uint32_t(countField(r, c, "crc32", UINT32_MAX))};
        uint64_t expected = uint64_t(voxelCount(n)) * l.components * l.elementBytes;
        if (e.bytes != expected)
            throw r.fail("chunk '" + name + "' holds " + std::to_string(e.bytes) + " bytes but grid " + dimsText +
                         " needs " + std::to_string(expected));
        if (e.offset > r.size() || dataStart + e.offset + e.bytes > r.size())
            throw r.fail("truncated: chunk '" + name + "' ends at byte " + std::to_string(dataStart + e.offset + e.bytes) +
                         " but the file has " + std::to_string(r.size()) + " bytes");
        table[name] = e;
    }
    return h;
}

}  // namespace

PreparedHeader readPreparedHeader(const fs::path& path) {
    Header h = readHeader(Reader(path));
    auto bytes = [&](const std::string& name) { return h.chunks.count(name) ? h.chunks.at(name).bytes : 0; };
    PreparedHeader out{h.prepared.classified.grid, std::move(h.prepared.meta), {bytes("pc"), 0, 0}};
    for (int o = 0; o < kOctants; ++o) {
        out.fieldBytes.acd += bytes("acd" + std::to_string(o));
        out.fieldBytes.eacd += bytes("eacd" + std::to_string(o));
    }
    return out;
}

PreparedVolume readPrepared(const fs::path& path, unsigned fields, bool normals) {
    Reader r(path);
    Header h = readHeader(r);
    PreparedVolume& p = h.prepared;
    const std::map<std::string, ChunkEntry>& table = h.chunks;
    const ExtentCode eacdCode = h.eacdCode;
    const Vec3i n = p.classified.grid.dims;

    // Gather the chunks to read, then read them all at once (see readChunks).
    auto has = [&](const std::string& name) { return table.count(name) > 0; };
    std::vector<ChunkRead> reads;
    // readHeader checked the table's sizes against the dims and the chunk's layout.
    auto want = [&](const std::string& name, auto& to) {
        const ChunkEntry& e = table.at(name);
        reads.push_back({name, e, destination(to, e.bytes, eacdCode)});
    };
    auto wantOctants = [&](const std::string& prefix, const char* label, auto& arrays) {
        for (int o = 0; o < kOctants; ++o) {
            std::string name = prefix + std::to_string(o);
            if (!has(name)) throw r.fail(std::string("has no ") + label + " distance field for octant " + std::to_string(o) +
                                         " (prepare it with volprep --fields)");
            want(name, arrays[o]);
        }
    };
    for (const char* required : {"sigma", "colour", "labels"})
        if (!has(required)) throw r.fail(std::string("has no '") + required + "' chunk");
    want("sigma", p.classified.sigma);
    want("colour", p.classified.colour);
    if (normals && has("normal")) want("normal", p.classified.normal);
    want("labels", p.regions.label);
    if (fields & (kFieldPC | kFieldACD | kFieldEACD)) p.fields.dims = n;
    if (fields & kFieldPC) {
        if (!has("pc")) throw r.fail("has no PC distance field (prepare it with volprep --fields)");
        want("pc", p.fields.pc);
    }
    if (fields & kFieldACD) wantOctants("acd", "ACD", p.fields.acd);
    if (fields & kFieldEACD) wantOctants("eacd", "EACD", p.fields.eacd);
    readChunks(r, h.dataStart, reads);

    // The labels must name regions that exist: whatever indexes per-region data by label relies on it.
    const std::vector<uint32_t>& label = p.regions.label;
    uint32_t maxLabel = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, label.size()), uint32_t(0),
        [&](const tbb::blocked_range<std::size_t>& b, uint32_t m) {
            return std::max(m, *std::max_element(label.begin() + std::ptrdiff_t(b.begin()), label.begin() + std::ptrdiff_t(b.end())));
        },
        [](uint32_t a, uint32_t b) { return std::max(a, b); });
    if (maxLabel >= p.regions.count)
        throw r.fail("labels hold region id " + std::to_string(maxLabel) + " but regionCount is " +
                     std::to_string(p.regions.count));
    return std::move(p);
}

}  // namespace vr
