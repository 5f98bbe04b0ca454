#include "io/prepared_header.h"

#include <fcntl.h>
#include <unistd.h>
#include <zstd.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "core/printable_text.h"
#include "io/crc32.h"
#include "io/prepared_chunks.h"
#include "io/prepared_file.h"
#include "io/ray_probe_json.h"

namespace vr::prepared_detail {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// The magic, the format version and the header's length, before the header.
constexpr std::size_t kPreambleBytes = sizeof(kMagic) + sizeof(uint32_t) + sizeof(uint64_t);
// Limits that catch a corrupted header before it turns into a huge allocation.
constexpr uint64_t kMaxHeaderBytes = uint64_t(1) << 30;
constexpr int kMaxDim = 1 << 16;
constexpr std::size_t kMaxVoxels = std::size_t(1) << 36;

constexpr ScalarType kScalarTypes[] = {ScalarType::UInt8, ScalarType::Int16, ScalarType::UInt16, ScalarType::Float32};

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

// A number (not a string or a bool) that `valid` accepts; `rule` says which ones do.
double numberField(const Reader& r, const json& j, const char* key, const std::string& name,
                   const std::function<bool(double)>& valid, const char* rule) {
    json v = field<json>(r, j, key);
    if (!v.is_number() || !valid(v.get<double>())) throw r.fail("bad header: '" + name + "' must be " + rule);
    return v.get<double>();
}

ScalarType scalarTypeField(const Reader& r, const json& header) {
    const auto name = field<std::string>(r, header, "scalarType");
    for (ScalarType t : kScalarTypes)
        if (scalarTypeName(t) == name) return t;
    throw r.fail("bad header: 'scalarType': unknown scalar type '" + name +
                 "' (expected uint8, int16, uint16 or float32)");
}

}  // namespace

Reader::Reader(const fs::path& path) : path_(path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw fail("no such file");
    if (!fs::is_regular_file(path, ec)) throw fail("not a regular file");
    size_ = fs::file_size(path, ec);
    if (ec) throw fail("cannot read: " + ec.message());
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw fail(std::string("cannot open: ") + std::strerror(errno));
}

Reader::~Reader() { ::close(fd_); }

void Reader::read(uint64_t offset, void* to, std::size_t bytes, const std::string& what) const {
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
        throw r.fail(std::string("bad header: ") + printableText(e.what()));
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
    GridGeometry& g = p.scalars.grid;
    g.dims = n;
    g.spacing = vec3Field(r, grid, "spacing");
    g.origin = vec3Field(r, grid, "origin");
    // A zero, negative or overflowing spacing makes every ray degenerate (a zero step never ends).
    for (int a = 0; a < 3; ++a)
        if (!(g.spacing[a] > 0) || !std::isfinite(g.origin[a]))
            throw r.fail("bad header: 'spacing' must be positive and 'origin' finite");
    if (!std::isfinite(length(g.extent()))) throw r.fail("bad header: 'spacing' x dims overflows (extent not finite)");
    p.scalars.sourceType = scalarTypeField(r, header);

    // How samples are classified: each number is checked here, the table's entries once they are read.
    ScalarClassification& c = p.classification;
    auto isFinite = [](double v) { return std::isfinite(v); };
    auto isPositive = [](double v) { return std::isfinite(v) && v > 0; };
    c.referenceStep = numberField(r, header, "referenceStep", "referenceStep", isPositive, "a finite number > 0");
    c.flatGradient = numberField(r, header, "flatGradient", "flatGradient",
                                 [](double v) { return std::isfinite(v) && v >= 0; }, "a finite number >= 0");
    json tf = field<json>(r, header, "transferTable");
    if (!tf.is_object()) throw r.fail("bad header: missing or invalid 'transferTable'");
    c.table.lo = numberField(r, tf, "lo", "transferTable.lo", isFinite, "a finite number");
    c.table.step = numberField(r, tf, "step", "transferTable.step", isPositive, "a finite number > 0");
    json entries = field<json>(r, tf, "entries");
    if (!entries.is_number_unsigned() || entries.get<uint64_t>() < 1 ||
        entries.get<uint64_t>() > kMaxTransferTableEntries)
        throw r.fail("bad header: 'transferTable.entries' must be an integer from 1 to " +
                     std::to_string(kMaxTransferTableEntries));
    h.tableEntries = entries.get<std::size_t>();
    if (!std::isfinite(c.table.lo + c.table.step * double(h.tableEntries - 1)))
        throw r.fail("bad header: 'transferTable' ends at a scalar that is not finite");

    p.regions.dims = n;
    p.regions.count = uint32_t(countField(r, header, "regionCount", UINT32_MAX));
    if (header.contains("labelMap")) {
        const json labels = field<json>(r, header, "labelMap");
        if (!labels.is_object()) throw r.fail("bad header: invalid 'labelMap'");
        const auto type = field<std::string>(r, labels, "type");
        if (type != "uint8" && type != "uint16")
            throw r.fail("bad header: 'labelMap.type': '" + type + "' (expected uint8 or uint16)");
        h.labelType = type == "uint8" ? ScalarType::UInt8 : ScalarType::UInt16;
        h.labelEntries = countField(r, labels, "entries", kMaxLabelEntries);
        if (h.labelEntries < 1) throw r.fail("bad header: 'labelMap.entries' must be at least 1");
        p.labels.emplace();
        p.labels->type = *h.labelType;
        p.labels->source = field<std::string>(r, labels, "source");
        p.labels->colourTable = field<std::string>(r, labels, "colourTable");
    }

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
    p.scalars.source = p.meta.source;
    ExtentCode& eacdCode = h.eacdCode;
    try {
        eacdCode = parseExtentCode(field<std::string>(r, header, "eacdCode"), "'eacdCode'");
    } catch (const InputError& e) {
        throw r.fail(std::string("bad header: ") + printableText(e.what()));
    }

    json compression = field<json>(r, header, "compression");
    if (!compression.is_object()) throw r.fail("bad header: missing or invalid 'compression'");
    const auto codec = field<std::string>(r, compression, "codec");
    if (codec != "zstd") throw r.fail("bad header: 'compression.codec': unknown codec '" + codec + "' (expected zstd)");
    const auto filter = field<std::string>(r, compression, "filter");
    if (filter != kSliceDeltaFilter)
        throw r.fail("bad header: 'compression.filter': unknown filter '" + filter + "' (expected " +
                     kSliceDeltaFilter + ")");
    json blockBytes = field<json>(r, compression, "blockBytes");
    if (!blockBytes.is_number_unsigned() || blockBytes.get<uint64_t>() < 1 ||
        blockBytes.get<uint64_t>() > kMaxPreparedBlockBytes)
        throw r.fail("bad header: 'compression.blockBytes' must be an integer from 1 to " +
                     std::to_string(kMaxPreparedBlockBytes));
    const uint64_t block = h.blockBytes = blockBytes.get<uint64_t>();

    // The chunk table must agree with the dims (the table chunk: with its entry count), its blocks with the chunk's
    // size, and every block must lie inside the file before anything is allocated.
    std::map<std::string, ChunkEntry>& table = h.chunks;
    for (const json& chunk : field<json>(r, header, "chunks")) {
        auto name = field<std::string>(r, chunk, "name");
        const bool labelChunk = name == "labelMap" || name == "labelTable";
        if (labelChunk && !h.labelType) throw r.fail("bad header: chunk '" + name + "' without a 'labelMap'");
        ChunkLayout l = layoutOf(name, eacdCode, p.scalars.sourceType, h.labelType.value_or(ScalarType::UInt8));
        if (l.type.empty()) throw r.fail("bad header: unknown chunk '" + name + "'");
        if (table.count(name)) throw r.fail("bad header: chunk '" + name + "' appears twice");
        if (field<std::string>(r, chunk, "type") != l.type ||
            countField(r, chunk, "components", kTableComponents) != uint64_t(l.components))
            throw r.fail("bad header: chunk '" + name + "' should be " + std::to_string(l.components) + " x " + l.type);
        ChunkEntry e;
        e.offset = countField(r, chunk, "offset", UINT64_MAX);
        e.bytes = countField(r, chunk, "bytes", UINT64_MAX);
        const bool isTable = isTableChunk(name);
        e.sliceBytes = sliceBytesOf(name, l, n);
        const std::size_t entries = name == "table" ? h.tableEntries : h.labelEntries;
        uint64_t expected = uint64_t(isTable ? entries : voxelCount(n)) * l.components * l.elementBytes;
        if (e.bytes != expected)
            throw r.fail("chunk '" + name + "' holds " + std::to_string(e.bytes) + " bytes but " +
                         (isTable ? std::string(name == "table" ? "a transfer table" : "a label table") + " of " +
                                        std::to_string(entries) + " entries"
                                  : "grid " + dimsText) +
                         " needs " + std::to_string(expected));
        const json blocks = field<json>(r, chunk, "blocks");
        const uint64_t count = e.bytes / block + (e.bytes % block != 0);
        if (!blocks.is_array() || blocks.size() != count)
            throw r.fail("chunk '" + name + "' has " + (blocks.is_array() ? std::to_string(blocks.size()) : "no") +
                         " blocks but " + std::to_string(e.bytes) + " bytes in blocks of " + std::to_string(block) +
                         " bytes make " + std::to_string(count));
        if (e.offset > r.size())
            throw r.fail("truncated: chunk '" + name + "' starts at byte " + std::to_string(dataStart + e.offset) +
                         " but the file has " + std::to_string(r.size()) + " bytes");
        // No overflow: the blocks' bounds add up to at most 64 times the chunk's bytes (< 2^38, from the dims).
        uint64_t at = dataStart + e.offset;
        for (std::size_t k = 0; k < count; ++k) {
            BlockEntry b{at, countField(r, blocks[k], "compressedBytes", UINT64_MAX),
                         std::min<uint64_t>(block, e.bytes - k * block),
                         uint32_t(countField(r, blocks[k], "crc32", UINT32_MAX))};
            const uint64_t bound = ZSTD_compressBound(b.bytes);
            if (b.stored < 1 || b.stored > bound)
                throw r.fail("chunk '" + name + "' block " + std::to_string(k) + " of " + std::to_string(count) +
                             " holds " + std::to_string(b.stored) + " compressed bytes (a zstd frame of " +
                             std::to_string(b.bytes) + " bytes takes 1 to " + std::to_string(bound) + ")");
            e.blocks.push_back(b);
            at += b.stored;
        }
        e.storedBytes = at - dataStart - e.offset;
        if (at > r.size())
            throw r.fail("truncated: chunk '" + name + "' ends at byte " + std::to_string(at) + " but the file has " +
                         std::to_string(r.size()) + " bytes");
        table[name] = e;
        h.order.push_back(name);
    }
    return h;
}

}  // namespace vr::prepared_detail
