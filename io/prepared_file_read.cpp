// Reading the prepared file: its header (io/prepared_header.h), then the chunks a render needs, read, checked and
// decompressed on all threads.
#include "io/prepared_file.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>

#include "io/crc32.h"
#include "io/prepared_checks.h"
#include "io/prepared_chunks.h"
#include "io/prepared_header.h"
#include "io/slice_delta.h"
#include "core/errors.h"

namespace vr {
namespace fs = std::filesystem;
using namespace prepared_detail;

namespace {

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
    if (crc32Of(frame, b.stored) != b.crc)
        return "chunk '" + chunk + "' checksum mismatch in" + block + " (file is corrupted)";
    const std::size_t frameBytes = ZSTD_findFrameCompressedSize(frame, b.stored);
    if (ZSTD_isError(frameBytes))
        return where + " cannot be decompressed (zstd: " + ZSTD_getErrorName(frameBytes) + ")";
    if (frameBytes != b.stored)
        return where + " holds " + std::to_string(b.stored) + " bytes but its zstd frame takes " +
               std::to_string(frameBytes);
    const unsigned long long content = ZSTD_getFrameContentSize(frame, b.stored);
    if (content == ZSTD_CONTENTSIZE_UNKNOWN || content == ZSTD_CONTENTSIZE_ERROR)
        return where + " does not state its decompressed size";
    if (content != b.bytes)
        return where + " decompresses to " + std::to_string(content) + " bytes but should hold " +
               std::to_string(b.bytes);
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

PreparedVolume readPrepared(const fs::path& path, unsigned fields, const PreparedReadScope& scope) {
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
            if (!(scope.octants >> o & 1u)) continue;
            std::string name = prefix + std::to_string(o);
            if (!has(name))
                throw r.fail(std::string("has no ") + label + " distance field for octant " + std::to_string(o) +
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
    } else if (!scope.floatScalars) {
        want("scalars", p.scalars.stored);
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
    if (scope.regions) want("labels", p.regions.label);
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
            throw r.fail("scalars hold " + floatText(values[bad]) + " at voxel " + std::to_string(bad) +
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
    if (label.empty()) return std::move(p);
    uint32_t maxLabel = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, label.size()), uint32_t(0),
        [&](const tbb::blocked_range<std::size_t>& b, uint32_t m) {
            return std::max(m, *std::max_element(label.begin() + std::ptrdiff_t(b.begin()),
                                                 label.begin() + std::ptrdiff_t(b.end())));
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
