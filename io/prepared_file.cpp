#include "io/prepared_file.h"

#include <fcntl.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "io/atomic_file.h"
#include "io/crc32.h"
#include "io/ray_probe_json.h"
#include "io/slice_delta.h"
#include "core/errors.h"
#include "core/extent_code.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;

// Chunks are stored as the in-memory arrays, so the file is little-endian only where the machine is.
static_assert(std::endian::native == std::endian::little, "the prepared format is little-endian");

namespace {

constexpr char kMagic[8] = {'V', 'O', 'L', 'P', 'R', 'E', 'P', '\0'};
// How the per-voxel chunks are coded before zstd (io/slice_delta.h).
constexpr const char* kSliceDeltaFilter = "sliceDelta";
constexpr std::size_t kPreambleBytes = sizeof(kMagic) + sizeof(uint32_t) + sizeof(uint64_t);
// Limits that catch a corrupted header before it turns into a huge allocation.
constexpr uint64_t kMaxHeaderBytes = uint64_t(1) << 30;
constexpr int kMaxDim = 1 << 16;
constexpr std::size_t kMaxVoxels = std::size_t(1) << 36;
// A table entry in the file: r, g, b, sigma (a label table's too).
constexpr int kTableComponents = 4;
// A label map's classes: one per label 0..65535 at most.
constexpr std::size_t kMaxLabelEntries = std::size_t(1) << 16;

constexpr ScalarType kScalarTypes[] = {ScalarType::UInt8, ScalarType::Int16, ScalarType::UInt16, ScalarType::Float32};

// What a chunk of a given name must hold: its element type and components per voxel (per entry for the table).
struct ChunkLayout {
    std::string type;  // empty: no such chunk
    int components;
    std::size_t elementBytes;
};

ChunkLayout layoutOf(const std::string& name, ExtentCode eacdCode, ScalarType scalarType, ScalarType labelType) {
    if (name == "scalars") return {std::string(scalarTypeName(scalarType)), 1, scalarBytes(scalarType)};
    if (name == "table") return {"float32", kTableComponents, 4};
    if (name == "labelMap") return {std::string(scalarTypeName(labelType)), 1, scalarBytes(labelType)};
    if (name == "labelTable") return {"float32", kTableComponents, 4};
    if (name == "labels") return {"uint32", 1, 4};
    if (name == "pc") return {"uint8", 1, 1};
    for (int o = 0; o < kOctants; ++o) {
        if (name == "acd" + std::to_string(o)) return {"uint8", 1, 1};
        if (name == "eacd" + std::to_string(o))
            return eacdCode == ExtentCode::Exact ? ChunkLayout{"uint8", 3, 1}
                   : eacdCode == ExtentCode::Log16 ? ChunkLayout{"uint16", 1, 2}
                                                   : ChunkLayout{"uint8", 1, 1};
    }
    return {"", 0, 0};
}

bool isTableChunk(const std::string& name) { return name == "table" || name == "labelTable"; }

// The bytes of one z slice of a chunk: a per-voxel chunk is stored as its differences over slices
// (io/slice_delta.h); 0 for the tables, stored as they are.
uint64_t sliceBytesOf(const std::string& name, const ChunkLayout& l, const Vec3i& dims) {
    return isTableChunk(name) ? 0 : uint64_t(dims.x) * uint64_t(dims.y) * uint64_t(l.components) * l.elementBytes;
}

// The first index in [0, n) where `bad` holds, or n: the lowest one, so that a message names the same voxel on
// every run.
template <typename Bad>
std::size_t firstWhere(std::size_t n, const Bad& bad) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n), n,
        [&](const tbb::blocked_range<std::size_t>& b, std::size_t found) {
            for (std::size_t i = b.begin(); i < b.end() && i < found; ++i)
                if (bad(i)) return i;
            return found;
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

std::string numberText(double v) {
    std::ostringstream s;
    s.precision(std::numeric_limits<float>::max_digits10);
    s << v;
    return s.str();
}

// The scalars in the file's type, encoded on all threads; returns the first voxel whose scalar the type does not
// hold exactly (narrowScalars), or values.size().
std::size_t encodeScalars(const std::vector<float>& values, ScalarType t, std::vector<char>& bytes) {
    bytes.resize(values.size() * scalarBytes(t));
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, values.size()), values.size(),
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t first) {
            unsigned char* to = reinterpret_cast<unsigned char*>(bytes.data()) + r.begin() * scalarBytes(t);
            const std::size_t bad = narrowScalars(values.data() + r.begin(), r.size(), t, to);
            return std::min(first, bad < r.size() ? r.begin() + bad : values.size());
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

template <typename T>
void decodeAs(const std::vector<char>& bytes, std::vector<float>& values) {
    const T* from = reinterpret_cast<const T*>(bytes.data());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, values.size()), [&](const tbb::blocked_range<std::size_t>& b) {
        for (std::size_t i = b.begin(); i < b.end(); ++i) values[i] = float(from[i]);
    });
}

void decodeScalars(const std::vector<char>& bytes, ScalarType t, std::vector<float>& values) {
    switch (t) {
        case ScalarType::UInt8: decodeAs<uint8_t>(bytes, values); break;
        case ScalarType::Int16: decodeAs<int16_t>(bytes, values); break;
        case ScalarType::UInt16: decodeAs<uint16_t>(bytes, values); break;
        case ScalarType::Float32: break;  // read straight into the values
    }
}

void splitTable(const std::vector<float>& in, TransferTable& t) {
    const std::size_t entries = in.size() / kTableComponents;
    t.sigma.resize(entries);
    t.colour.resize(entries);
    for (std::size_t i = 0; i < entries; ++i) {
        const float* e = &in[i * kTableComponents];
        t.colour[i] = {e[0], e[1], e[2]};
        t.sigma[i] = e[3];
    }
}

// What is wrong with a table's entries (a renderer takes exp(-sigma L) and blends the colours), if anything.
std::optional<std::string> tableEntryProblem(const TransferTable& t) {
    for (std::size_t i = 0; i < t.size(); ++i) {
        const auto& c = t.colour[i];
        if (!(std::isfinite(t.sigma[i]) && t.sigma[i] >= 0))
            return "transfer table entry " + std::to_string(i) + " has sigma " + numberText(t.sigma[i]) +
                   " (must be finite and >= 0)";
        if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
            return "transfer table entry " + std::to_string(i) + " has a colour that is not finite";
    }
    return std::nullopt;
}

// What is wrong with a label map's classes (a renderer adds their sigma and blends their colours), if anything.
std::optional<std::string> labelClassProblem(const LabelClasses& c) {
    for (std::size_t i = 0; i < c.size(); ++i)
        if (!(std::isfinite(c.sigma[i]) && c.sigma[i] >= 0) || !std::isfinite(c.colour[i][0]) ||
            !std::isfinite(c.colour[i][1]) || !std::isfinite(c.colour[i][2]))
            return "label " + std::to_string(i) + "'s class has a sigma that is not finite and >= 0 or a colour that "
                   "is not finite";
    return std::nullopt;
}

// What is wrong with the classification's numbers (the header's referenceStep, flatGradient and transferTable),
// if anything: the writer refuses what the reader would.
std::optional<std::string> classificationProblem(const ScalarClassification& c) {
    const TransferTable& t = c.table;
    if (!(std::isfinite(c.referenceStep) && c.referenceStep > 0)) return "'referenceStep' must be a finite number > 0";
    if (!(std::isfinite(c.flatGradient) && c.flatGradient >= 0)) return "'flatGradient' must be a finite number >= 0";
    if (!std::isfinite(t.lo)) return "'transferTable.lo' must be a finite number";
    if (!(std::isfinite(t.step) && t.step > 0)) return "'transferTable.step' must be a finite number > 0";
    if (!std::isfinite(t.lo + t.step * double(t.size() == 0 ? 0 : t.size() - 1)))
        return "'transferTable' ends at a scalar that is not finite";
    return std::nullopt;
}

// One array of the PreparedVolume, as bytes, on its way into the file.
struct ChunkSource {
    std::string name;
    const void* data;
    std::size_t elements;  // voxels (table: entries) present (0: chunk absent)
};

template <typename T>
ChunkSource source(std::string name, const std::vector<T>& v) {
    return {std::move(name), v.data(), v.size()};
}

// The chunks that hold the distance fields, those present.
std::vector<ChunkSource> fieldSources(const PreparedVolume& p) {
    std::vector<ChunkSource> all = {source("pc", p.fields.pc)};
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
    const GridGeometry& g = p.grid();
    const TransferTable& t = p.classification.table;
    auto fail = [&](const std::string& what) { return fileError(path.string(), "cannot write: " + what); };
    if (g.dims.x < 1 || g.dims.y < 1 || g.dims.z < 1) throw fail("empty grid");
    if (p.scalars.values.size() != g.voxels()) throw fail("the scalars must hold one value per voxel");
    if (p.regions.dims != g.dims) throw fail("region labels and scalars have different dims");
    if (p.regions.label.size() != g.voxels()) throw fail("the labels must hold one value per voxel");
    bool anyField = p.fields.hasPC() || p.fields.hasACD() || p.fields.hasEACD();
    if (anyField && p.fields.dims != g.dims) throw fail("distance fields and scalars have different dims");
    if (t.sigma.size() != t.colour.size()) throw fail("the transfer table's sigma and colour differ in size");
    if (t.size() < 1 || t.size() > kMaxTransferTableEntries)
        throw fail("the transfer table holds " + std::to_string(t.size()) + " entries (must be 1 to " +
                   std::to_string(kMaxTransferTableEntries) + ")");
    if (auto problem = classificationProblem(p.classification)) throw fail(*problem);
    if (auto problem = tableEntryProblem(t)) throw fail(*problem);
    for (const ChunkSource& c : fieldSources(p))
        if (c.elements != g.voxels()) throw fail("chunk '" + c.name + "' does not hold one value per voxel");
    for (int o = 1; o < kOctants; ++o)
        if (p.fields.acd[o].empty() != p.fields.acd[0].empty() || p.fields.eacd[o].empty() != p.fields.eacd[0].empty())
            throw fail("ACD and EACD need all 8 octants or none");
    for (const ExtentField& octant : p.fields.eacd)
        if (octant.code() != p.fields.eacdCode()) throw fail("the EACD octants are in different codes");
    if (const auto& labels = p.labels) {
        const LabelClasses& c = labels->classes;
        if (labels->label.size() != g.voxels()) throw fail("the label map must hold one label per voxel");
        if (labels->type != ScalarType::UInt8 && labels->type != ScalarType::UInt16)
            throw fail("the label map's type must be uint8 or uint16");
        if (c.size() < 1 || c.size() > kMaxLabelEntries || c.colour.size() != c.size())
            throw fail("the label map's classes hold " + std::to_string(c.size()) + " labels (must be 1 to " +
                       std::to_string(kMaxLabelEntries) + ")");
        if (auto problem = labelClassProblem(c)) throw fail(*problem);
        if (labels->type == ScalarType::UInt8 &&
            std::any_of(labels->label.begin(), labels->label.end(), [](uint16_t l) { return l > 255; }))
            throw fail("the label map's uint8 type does not hold its labels");
    }
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

// What is wrong with a block whose frame is at `frame`, if anything; decompressed into `to` when nothing is. The
// frame's CRC-32 is checked before zstd reads it; then it must be one zstd frame that states the block's size and
// decompresses to exactly that.
std::string decodeBlock(const char* frame, const BlockEntry& b, char* to, const std::string& chunk, std::size_t k,
                        std::size_t blocks) {
    const std::string block = " block " + std::to_string(k) + " of " + std::to_string(blocks);
    const std::string where = "chunk '" + chunk + "'" + block;
    if (crc32Of(frame, b.stored) != b.crc) return "chunk '" + chunk + "' checksum mismatch in" + block + " (file is corrupted)";
    const std::size_t frameBytes = ZSTD_findFrameCompressedSize(frame, b.stored);
    if (ZSTD_isError(frameBytes)) return where + " cannot be decompressed (zstd: " + ZSTD_getErrorName(frameBytes) + ")";
    if (frameBytes != b.stored)
        return where + " holds " + std::to_string(b.stored) + " bytes but its zstd frame takes " + std::to_string(frameBytes);
    const unsigned long long content = ZSTD_getFrameContentSize(frame, b.stored);
    if (content == ZSTD_CONTENTSIZE_UNKNOWN || content == ZSTD_CONTENTSIZE_ERROR)
        return where + " does not state its decompressed size";
    if (content != b.bytes)
        return where + " decompresses to " + std::to_string(content) + " bytes but should hold " + std::to_string(b.bytes);
    const std::size_t got = ZSTD_decompress(to, b.bytes, frame, b.stored);
    if (ZSTD_isError(got)) return where + " cannot be decompressed (zstd: " + ZSTD_getErrorName(got) + ")";
    if (got != b.bytes)
        return where + " decompresses to " + std::to_string(got) + " bytes but should hold " + std::to_string(b.bytes);
    return {};
}

// Allocates every destination (in parallel: the page faults are a large part of the cost), then reads, checks and
// decompresses the blocks of all chunks in parallel, each straight into its place in the destination. A problem is
// reported for the first bad block in the order of `reads`, so that the message does not depend on the threads.
void readChunks(const Reader& r, const std::vector<ChunkRead>& reads) {
    std::vector<char*> data(reads.size());
    tbb::parallel_for(std::size_t(0), reads.size(), [&](std::size_t i) { data[i] = reads[i].allocate(); });

    struct Job {
        std::size_t chunk, block;
        uint64_t to;  // where its bytes go in the chunk
    };
    std::vector<Job> jobs;
    for (std::size_t i = 0; i < reads.size(); ++i) {
        uint64_t to = 0;
        for (std::size_t k = 0; k < reads[i].entry.blocks.size(); ++k) {
            jobs.push_back({i, k, to});
            to += reads[i].entry.blocks[k].bytes;
        }
    }
    std::vector<std::string> problems(jobs.size());
    tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t j) {
        const Job& job = jobs[j];
        const ChunkRead& c = reads[job.chunk];
        const BlockEntry& b = c.entry.blocks[job.block];
        std::unique_ptr<char[]> frame(new char[b.stored]);
        r.read(b.at, frame.get(), b.stored, "chunk '" + c.name + "'");
        char* to = data[job.chunk] + job.to;
        problems[j] = decodeBlock(frame.get(), b, to, c.name, job.block, c.entry.blocks.size());
        if (problems[j].empty() && c.entry.sliceBytes > 0)
            sliceDeltaDecode(reinterpret_cast<unsigned char*>(to), b.bytes, c.entry.sliceBytes);
    });
    for (const std::string& problem : problems)
        if (!problem.empty()) throw r.fail(problem);
}

}  // namespace

void writePrepared(const fs::path& path, const PreparedVolume& p, const PreparedWriteOptions& options) {
    checkSizes(path, p);
    if (options.blockBytes < 1 || options.blockBytes > kMaxPreparedBlockBytes)
        throw fileError(path.string(), "cannot write: blocks of " + std::to_string(options.blockBytes) +
                                           " bytes (must be 1 to " + std::to_string(kMaxPreparedBlockBytes) + ")");
    if (options.zstdLevel < ZSTD_minCLevel() || options.zstdLevel > ZSTD_maxCLevel())
        throw fileError(path.string(), "cannot write: zstd level " + std::to_string(options.zstdLevel) + " (must be " +
                                           std::to_string(ZSTD_minCLevel()) + " to " +
                                           std::to_string(ZSTD_maxCLevel()) + ")");
    const GridGeometry& g = p.grid();
    const ExtentCode code = p.fields.eacdCode();
    const ScalarType scalarType = p.scalars.sourceType;
    const TransferTable& tf = p.classification.table;
    std::vector<char> scalars;
    if (const std::size_t bad = encodeScalars(p.scalars.values, scalarType, scalars); bad < p.scalars.values.size())
        throw fileError(path.string(), "cannot write: scalar " + numberText(p.scalars.values[bad]) + " at voxel " +
                                           std::to_string(bad) + " is not a " +
                                           std::string(scalarTypeName(scalarType)) + " value");
    const std::vector<float> entries = tf.interleaved();
    std::vector<ChunkSource> chunks = {{"scalars", scalars.data(), p.scalars.values.size()},
                                       {"table", entries.data(), tf.size()},
                                       source("labels", p.regions.label)};
    // A label map's labels in its own type (8 bits where they fit) and its classes as the table's entries.
    const ScalarType labelType = p.labels ? p.labels->type : ScalarType::UInt8;
    std::vector<unsigned char> labelBytes;
    std::vector<float> labelEntries;
    if (p.labels) {
        labelBytes.resize(p.labels->label.size() * scalarBytes(labelType));
        if (labelType == ScalarType::UInt16) std::memcpy(labelBytes.data(), p.labels->label.data(), labelBytes.size());
        else std::copy(p.labels->label.begin(), p.labels->label.end(), labelBytes.begin());
        labelEntries = p.labels->classes.interleaved();
        chunks.push_back({"labelMap", labelBytes.data(), p.labels->label.size()});
        chunks.push_back({"labelTable", labelEntries.data(), p.labels->classes.size()});
    }
    for (ChunkSource& c : fieldSources(p)) chunks.push_back(std::move(c));

    // Every block of every chunk is compressed on its own (one zstd frame stating its size), all on all threads,
    // and checksummed as stored.
    struct Block {
        std::size_t chunk;
        uint64_t begin, bytes;                // in the chunk, uncompressed
        std::unique_ptr<char[]> frame;        // its `stored` bytes
        std::size_t stored = 0;
        uint32_t crc = 0;
    };
    std::vector<uint64_t> chunkBytes, sliceBytes;
    std::vector<Block> blocks;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        ChunkLayout l = layoutOf(chunks[i].name, code, scalarType, labelType);
        chunkBytes.push_back(uint64_t(chunks[i].elements) * l.components * l.elementBytes);
        sliceBytes.push_back(sliceBytesOf(chunks[i].name, l, g.dims));
        for (uint64_t b = 0; b < chunkBytes[i]; b += options.blockBytes)
            blocks.push_back({i, b, std::min<uint64_t>(options.blockBytes, chunkBytes[i] - b), nullptr});
    }
    // Each thread keeps its zstd context and a frame's worth of scratch from block to block: making them afresh
    // per block (and faulting in their pages) took 40 % of the write.
    using Context = std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)>;
    tbb::enumerable_thread_specific<Context> contexts([] { return Context(ZSTD_createCCtx(), &ZSTD_freeCCtx); });
    tbb::enumerable_thread_specific<std::vector<char>> scratches;
    tbb::enumerable_thread_specific<std::vector<unsigned char>> differences;
    tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t k) {
        Block& b = blocks[k];
        Context& context = contexts.local();
        if (!context) throw std::bad_alloc();
        std::vector<char>& scratch = scratches.local();
        scratch.resize(std::max(scratch.size(), ZSTD_compressBound(b.bytes)));
        const unsigned char* from = static_cast<const unsigned char*>(chunks[b.chunk].data) + b.begin;
        if (sliceBytes[b.chunk] > 0) {
            std::vector<unsigned char>& d = differences.local();
            d.resize(std::max<std::size_t>(d.size(), b.bytes));
            sliceDeltaEncode(from, b.bytes, sliceBytes[b.chunk], d.data());
            from = d.data();
        }
        b.stored = ZSTD_compressCCtx(context.get(), scratch.data(), scratch.size(), from, b.bytes, options.zstdLevel);
        if (ZSTD_isError(b.stored))
            throw fileError(path.string(), std::string("cannot write: zstd: ") + ZSTD_getErrorName(b.stored));
        b.frame.reset(new char[b.stored]);
        std::memcpy(b.frame.get(), scratch.data(), b.stored);
        b.crc = crc32Of(b.frame.get(), b.stored);
    });

    json table = json::array();
    uint64_t offset = 0;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        ChunkLayout l = layoutOf(chunks[i].name, code, scalarType, labelType);
        const uint64_t chunkOffset = offset;
        json stored = json::array();
        for (const Block& b : blocks)
            if (b.chunk == i) {
                stored.push_back({{"compressedBytes", b.stored}, {"crc32", b.crc}});
                offset += b.stored;
            }
        table.push_back({{"name", chunks[i].name},
                         {"type", l.type},
                         {"components", l.components},
                         {"bytes", chunkBytes[i]},
                         {"offset", chunkOffset},
                         {"blocks", stored}});
    }
    json header = {{"grid",
                    {{"dims", {g.dims.x, g.dims.y, g.dims.z}}, {"spacing", vec3Json(g.spacing)}, {"origin", vec3Json(g.origin)}}},
                   {"scalarType", scalarTypeName(scalarType)},
                   {"referenceStep", p.classification.referenceStep},
                   {"flatGradient", p.classification.flatGradient},
                   {"transferTable", {{"lo", tf.lo}, {"step", tf.step}, {"entries", tf.size()}}},
                   {"regionCount", p.regions.count},

                   {"metadata", metadataJson(p.meta)},
                   {"eacdCode", extentCodeName(code)},
                   {"compression",
                    {{"codec", "zstd"},
                     {"filter", kSliceDeltaFilter},
                     {"level", options.zstdLevel},
                     {"blockBytes", options.blockBytes}}},
                   {"chunks", table}};
    if (p.labels)
        header["labelMap"] = {{"type", scalarTypeName(labelType)},
                              {"entries", p.labels->classes.size()},
                              {"source", p.labels->source},
                              {"colourTable", p.labels->colourTable}};
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
        for (const Block& b : blocks) out.write(b.frame.get(), std::streamsize(b.stored));
    });
}

namespace {

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
    throw r.fail("bad header: 'scalarType': unknown scalar type '" + name + "' (expected uint8, int16, uint16 or float32)");
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
    if (!entries.is_number_unsigned() || entries.get<uint64_t>() < 1 || entries.get<uint64_t>() > kMaxTransferTableEntries)
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
        throw r.fail(std::string("bad header: ") + e.what());
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

}  // namespace

PreparedHeader readPreparedHeader(const fs::path& path) {
    Header h = readHeader(Reader(path));
    auto bytes = [&](const std::string& name) { return h.chunks.count(name) ? h.chunks.at(name).bytes : 0; };
    PreparedHeader out{h.prepared.grid(), h.prepared.scalars.sourceType, h.tableEntries, std::move(h.prepared.meta),
                       {bytes("pc"), 0, 0}, {}};
    for (const std::string& name : h.order)
        out.chunks.push_back({name, h.chunks.at(name).bytes, h.chunks.at(name).storedBytes});
    for (int o = 0; o < kOctants; ++o) {
        out.fieldBytes.acd += bytes("acd" + std::to_string(o));
        out.fieldBytes.eacd += bytes("eacd" + std::to_string(o));
    }
    return out;
}

PreparedVolume readPrepared(const fs::path& path, unsigned fields) {
    Reader r(path);
    Header h = readHeader(r);
    PreparedVolume& p = h.prepared;
    const std::map<std::string, ChunkEntry>& table = h.chunks;
    const ExtentCode eacdCode = h.eacdCode;
    const Vec3i n = p.grid().dims;
    const std::size_t voxels = p.grid().voxels();
    const ScalarType scalarType = p.scalars.sourceType;

    // Gather the chunks to read, then read them all at once (see readChunks).
    auto has = [&](const std::string& name) { return table.count(name) > 0; };
    std::vector<ChunkRead> reads;
    // readHeader checked the table's sizes against the dims (the table chunk: the entry count) and the layouts.
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
    for (const char* required : {"scalars", "table", "labels"})
        if (!has(required)) throw r.fail(std::string("has no '") + required + "' chunk");
    // Float scalars are read straight into the values; integer ones into their own type, converted after.
    std::vector<char> scalarBytesRead;
    std::vector<float>& values = p.scalars.values;
    if (scalarType == ScalarType::Float32) {
        want("scalars", values);
    } else {
        const ChunkEntry& e = table.at("scalars");
        reads.push_back({"scalars", e, [&values, &scalarBytesRead, bytes = e.bytes, voxels] {
                             values.resize(voxels);  // allocated beside the other destinations
                             scalarBytesRead.resize(bytes);
                             return scalarBytesRead.data();
                         }});
    }
    std::vector<float> entries;
    want("table", entries);
    want("labels", p.regions.label);
    std::vector<uint8_t> labelBytes;
    std::vector<float> labelEntries;
    if (h.labelType) {
        for (const char* required : {"labelMap", "labelTable"})
            if (!has(required)) throw r.fail(std::string("has a label map but no '") + required + "' chunk");
        want("labelMap", labelBytes);
        want("labelTable", labelEntries);
    }
    if (fields & (kFieldPC | kFieldACD | kFieldEACD)) p.fields.dims = n;
    if (fields & kFieldPC) {
        if (!has("pc")) throw r.fail("has no PC distance field (prepare it with volprep --fields)");
        want("pc", p.fields.pc);
    }
    if (fields & kFieldACD) wantOctants("acd", "ACD", p.fields.acd);
    if (fields & kFieldEACD) wantOctants("eacd", "EACD", p.fields.eacd);
    readChunks(r, reads);

    decodeScalars(scalarBytesRead, scalarType, values);
    std::vector<char>().swap(scalarBytesRead);
    if (scalarType == ScalarType::Float32) {
        // Loaders refuse a volume with a non-finite voxel; a renderer's table lookup relies on it.
        const std::size_t bad = firstWhere(values.size(), [&](std::size_t i) { return !std::isfinite(values[i]); });
        if (bad < values.size())
            throw r.fail("scalars hold " + numberText(values[bad]) + " at voxel " + std::to_string(bad) +
                         " (must be finite)");
    }
    splitTable(entries, p.classification.table);
    if (auto problem = tableEntryProblem(p.classification.table)) throw r.fail(*problem);
    if (p.labels) {
        std::vector<uint16_t>& l = p.labels->label;
        l.resize(voxels);
        if (p.labels->type == ScalarType::UInt16) std::memcpy(l.data(), labelBytes.data(), labelBytes.size());
        else std::copy(labelBytes.begin(), labelBytes.end(), l.begin());
        splitTable(labelEntries, p.labels->classes);  // the same four floats an entry
        if (auto problem = labelClassProblem(p.labels->classes)) throw r.fail(*problem);
    }

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

bool isPreparedFile(const fs::path& path) {
    char head[sizeof kMagic] = {};
    std::ifstream in(path, std::ios::binary);
    return in.read(head, sizeof head) && std::memcmp(head, kMagic, sizeof kMagic) == 0;
}

}  // namespace vr
