// Writing the prepared file: checks what it is given, compresses its chunks on all threads, writes it atomically.
#include "io/prepared_file.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <zstd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <memory>

#include "io/atomic_file.h"
#include "io/crc32.h"
#include "io/prepared_checks.h"
#include "io/prepared_chunks.h"
#include "io/ray_probe_json.h"
#include "io/slice_delta.h"
#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace prepared_detail;

namespace {

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
        throw fileError(path.string(), "cannot write: scalar " + floatText(p.scalars.values[bad]) + " at voxel " +
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
    // Compression takes most of the time; the file's write the rest (kCompressedShare of a 512^3 CT's on 2 cores).
    constexpr double kCompressedShare = 0.9;
    std::atomic<std::size_t> compressed{0};
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
        reportProgress(options.progress, kCompressedShare * double(++compressed) / double(blocks.size()));
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
                    {{"dims", {g.dims.x, g.dims.y, g.dims.z}},
                     {"spacing", vec3Json(g.spacing)},
                     {"origin", vec3Json(g.origin)}}},
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

}  // namespace vr
