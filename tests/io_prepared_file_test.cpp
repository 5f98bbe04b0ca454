// The prepared file: exact round trip, selective reading, its zstd blocks, and a clear InputError for every kind of
// damage.
#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

#include "core/errors.h"
#include "core/extent_code.h"
#include "io/prepared_file.h"
#include "io/slice_delta.h"
#include "datasets/phantoms.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr ScalarType kEveryScalarType[] = {ScalarType::UInt8, ScalarType::Int16, ScalarType::UInt16,
                                           ScalarType::Float32};

// Noise in [0, 255] as a volume of `type`: int16 reaches below zero, uint16 above 255, float32 has fractions.
float scalarOf(float noise, ScalarType type) {
    switch (type) {
        case ScalarType::UInt8: return noise;
        case ScalarType::Int16: return (noise - 128) * 100;  // -12800 .. 12700
        case ScalarType::UInt16: return noise * 250;         // 0 .. 63750
        case ScalarType::Float32: return noise * 0.37f - 5.125f;
    }
    return 0;
}

// A transfer table of 37 entries whose every value differs, with numbers that do not round trip through a
// decimal of few digits.
ScalarClassification sampleClassification() {
    ScalarClassification c;
    c.referenceStep = 0.5;
    c.flatGradient = 1.0 / 3.0e5;
    c.table.lo = -1024.1234567890123;
    c.table.step = 0.1;
    for (int i = 0; i < 37; ++i) {
        c.table.sigma.push_back(i == 0 ? 0.0f : i == 1 ? std::numeric_limits<float>::denorm_min() : float(i) / 3.0f);
        c.table.colour.push_back({float(i) / 37, 1 - float(i) / 37, i % 2 ? 0.1f : 1.0f});
    }
    return c;
}

// A prepared volume with every chunk present and distinct, reproducible contents (not a real segmentation:
// the format must carry any bytes).
PreparedVolume samplePrepared(Vec3i dims, ScalarType type = ScalarType::Int16) {
    Volume noise = noisePhantom(dims, 7, 0, 255, {0.5, 0.75, 2.0});
    PreparedVolume p;
    p.scalars.grid = noise.grid;
    p.scalars.grid.origin = {-1.5, 2.25, 3};
    p.scalars.sourceType = type;
    p.classification = sampleClassification();
    std::size_t n = noise.grid.voxels();
    for (std::size_t i = 0; i < n; ++i) {
        float f = noise.values[i];
        p.scalars.values.push_back(scalarOf(f, type));
        p.regions.label.push_back(uint32_t(f) / 16);
    }
    p.regions.dims = dims;
    p.regions.count = 16;
    p.fields.dims = dims;
    for (std::size_t i = 0; i < n; ++i) p.fields.pc.push_back(uint8_t(noise.values[i]) % 7);
    for (int o = 0; o < kOctants; ++o) {
        std::vector<Extents> boxes;
        for (std::size_t i = 0; i < n; ++i) {
            uint8_t a = uint8_t(1 + (uint8_t(noise.values[i]) + o) % 9);
            p.fields.acd[o].push_back(a);
            boxes.push_back({a, uint8_t(a + o), uint8_t(a + 2 * o)});
        }
        p.fields.eacd[o] = ExtentField(ExtentCode::Exact, boxes);
    }
    p.meta.source = "phantom:noise";
    p.meta.classification = R"([{"Points": [0, 0, 0.5, 0, 255, 1, 0.5, 0]}])";
    p.meta.segmentation = {0.01, 3.0, true, true};
    p.meta.statistics = {{"voxels", n}, {"regions", 16}};
    RayProbe& probe = p.meta.rayProbe.emplace();
    probe.stepVoxels = 0.5;
    probe.ert = 0.99;
    probe.octantViews = 16;
    probe.quadrantViews = 6;
    probe.axisViews = 8;
    probe.acd.emplace();
    for (int c = 0; c < kProbeDirectionClasses; ++c) {
        probe.primitive.singleSamples[c] = 100 + c;
        probe.acd->leaps[c] = 0.25 * c;
    }
    return p;
}

std::vector<char> readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::vector<char>& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

// The parts of a prepared file, to damage one of them precisely.
struct Parts {
    std::vector<char> preamble;  // magic, version, header length
    json header;
    std::vector<char> data;      // everything after the header checksum
};

Parts split(const fs::path& p) {
    std::vector<char> b = readBytes(p);
    uint64_t len;
    std::memcpy(&len, b.data() + 12, 8);
    Parts parts;
    parts.preamble.assign(b.begin(), b.begin() + 20);
    parts.header = json::parse(std::string(b.begin() + 20, b.begin() + 20 + std::ptrdiff_t(len)));
    parts.data.assign(b.begin() + 20 + std::ptrdiff_t(len) + 4, b.end());
    return parts;
}

// Reassembles a file with a consistent header length and header checksum, so that only the edit is wrong.
void join(const fs::path& p, const Parts& parts) {
    std::string text = parts.header.dump();
    uint64_t len = text.size();
    uint32_t crc = uint32_t(crc32_z(0, reinterpret_cast<const Bytef*>(text.data()), text.size()));
    std::vector<char> b(parts.preamble);
    std::memcpy(b.data() + 12, &len, 8);
    b.insert(b.end(), text.begin(), text.end());
    b.insert(b.end(), reinterpret_cast<const char*>(&crc), reinterpret_cast<const char*>(&crc) + 4);
    b.insert(b.end(), parts.data.begin(), parts.data.end());
    writeBytes(p, b);
}

uint64_t dataStart(const fs::path& p) {
    std::vector<char> b = readBytes(p);
    uint64_t len;
    std::memcpy(&len, b.data() + 12, 8);
    return 20 + len + 4;
}

json chunkEntry(const json& header, const std::string& name) {
    for (const json& c : header.at("chunks"))
        if (c["name"] == name) return c;
    ADD_FAILURE() << "no chunk " << name;
    return {};
}

json& chunkEntryToEdit(json& header, const std::string& name) {
    for (json& c : header.at("chunks"))
        if (c["name"] == name) return c;
    throw std::runtime_error("no chunk " + name);
}

uint32_t crcOf(const std::vector<char>& bytes) {
    return uint32_t(crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

// One zstd frame of `n` bytes at `data`, stating its size unless `statesSize` is false.
std::vector<char> compress(const char* data, std::size_t n, int level = 1, bool statesSize = true) {
    std::vector<char> frame(ZSTD_compressBound(n));
    ZSTD_CCtx* context = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, level);
    ZSTD_CCtx_setParameter(context, ZSTD_c_contentSizeFlag, statesSize ? 1 : 0);
    const std::size_t stored = ZSTD_compress2(context, frame.data(), frame.size(), data, n);
    ZSTD_freeCCtx(context);
    if (ZSTD_isError(stored)) throw std::runtime_error(ZSTD_getErrorName(stored));
    frame.resize(stored);
    return frame;
}

// A chunk's blocks as the file stores them: zstd frames, in order.
std::vector<std::vector<char>> storedBlocks(const Parts& parts, const std::string& name) {
    const json c = chunkEntry(parts.header, name);
    std::vector<std::vector<char>> blocks;
    uint64_t at = c["offset"].get<uint64_t>();
    for (const json& b : c["blocks"]) {
        const uint64_t n = b["compressedBytes"].get<uint64_t>();
        blocks.emplace_back(parts.data.begin() + std::ptrdiff_t(at), parts.data.begin() + std::ptrdiff_t(at + n));
        at += n;
    }
    return blocks;
}

// A chunk's stored bytes, its blocks decompressed.
std::vector<char> storedBytes(const Parts& parts, const std::string& name) {
    std::vector<char> bytes;
    for (const std::vector<char>& frame : storedBlocks(parts, name)) {
        const unsigned long long n = ZSTD_getFrameContentSize(frame.data(), frame.size());
        if (n == ZSTD_CONTENTSIZE_UNKNOWN || n == ZSTD_CONTENTSIZE_ERROR)
            throw std::runtime_error("frame without size");
        const std::size_t at = bytes.size();
        bytes.resize(at + n);
        if (ZSTD_decompress(bytes.data() + at, n, frame.data(), frame.size()) != n)
            throw std::runtime_error("bad frame");
    }
    return bytes;
}

// The bytes of one z slice of a per-voxel chunk, whose bytes are stored as differences over slices; 0 for a table.
uint64_t sliceBytes(const Parts& parts, const std::string& name) {
    if (name == "table" || name == "labelTable") return 0;
    const json& dims = parts.header["grid"]["dims"];
    const uint64_t voxels = dims[0].get<uint64_t>() * dims[1].get<uint64_t>() * dims[2].get<uint64_t>();
    return chunkEntry(parts.header, name)["bytes"].get<uint64_t>() / voxels * dims[0].get<uint64_t>() *
           dims[1].get<uint64_t>();
}

// A chunk's bytes as the array holds them: its blocks decompressed, and a per-voxel chunk's blocks decoded.
std::vector<char> chunkBytes(const Parts& parts, const std::string& name) {
    std::vector<char> bytes = storedBytes(parts, name);
    const uint64_t block = parts.header["compression"]["blockBytes"].get<uint64_t>();
    if (const uint64_t slice = sliceBytes(parts, name))
        for (uint64_t b = 0; b < bytes.size(); b += block)
            sliceDeltaDecode(reinterpret_cast<unsigned char*>(bytes.data() + b),
                             std::min<uint64_t>(block, bytes.size() - b), slice);
    return bytes;
}

// Stores `blocks` as chunk `name`'s (their entries take the new sizes and CRC-32s), moving the chunks after it, so
// that the chunk table is consistent but for what the blocks hold.
void replaceBlocks(Parts& parts, const std::string& name, const std::vector<std::vector<char>>& blocks) {
    std::vector<std::vector<std::vector<char>>> all;
    for (const json& c : parts.header["chunks"])
        all.push_back(c["name"] == name ? blocks : storedBlocks(parts, c["name"].get<std::string>()));
    parts.data.clear();
    for (std::size_t i = 0; i < all.size(); ++i) {
        json& c = parts.header["chunks"][i];
        c["offset"] = parts.data.size();
        c["blocks"] = json::array();
        for (const std::vector<char>& frame : all[i]) {
            c["blocks"].push_back({{"compressedBytes", frame.size()}, {"crc32", crcOf(frame)}});
            parts.data.insert(parts.data.end(), frame.begin(), frame.end());
        }
    }
}

// Stores `array` as chunk `name` (coded over slices where it is per voxel), compressed in blocks of the header's
// size.
void rewriteChunk(Parts& parts, const std::string& name, const std::vector<char>& array) {
    const uint64_t block = parts.header["compression"]["blockBytes"].get<uint64_t>();
    const uint64_t slice = sliceBytes(parts, name);
    std::vector<std::vector<char>> blocks;
    for (uint64_t b = 0; b < array.size(); b += block) {
        const uint64_t n = std::min<uint64_t>(block, array.size() - b);
        std::vector<char> bytes(array.begin() + std::ptrdiff_t(b), array.begin() + std::ptrdiff_t(b + n));
        if (slice > 0)
            sliceDeltaEncode(reinterpret_cast<const unsigned char*>(array.data() + b), n, slice,
                             reinterpret_cast<unsigned char*>(bytes.data()));
        blocks.push_back(compress(bytes.data(), n));
    }
    replaceBlocks(parts, name, blocks);
}

// Overwrites `size` bytes of chunk `name` from `at` (bytes into the chunk, uncompressed) and compresses it again,
// so that the chunk is well formed but holds what the writer would refuse.
void patchChunk(Parts& parts, const std::string& name, uint64_t at, const void* bytes, std::size_t size) {
    std::vector<char> plain = chunkBytes(parts, name);
    std::memcpy(plain.data() + at, bytes, size);
    rewriteChunk(parts, name, plain);
}

// The bytes of an array, to compare with a chunk's.
template <typename T>
std::vector<char> bytesOf(const std::vector<T>& v) {
    const char* p = reinterpret_cast<const char*>(v.data());
    return {p, p + v.size() * sizeof(T)};
}

// readPrepared must throw an InputError naming the file and containing `problem`.
void expectRejected(const fs::path& p, const std::string& problem,
                    unsigned fields = kFieldPC | kFieldACD | kFieldEACD) {
    try {
        readPrepared(p, fields);
        ADD_FAILURE() << "read of " << p << " succeeded; expected: " << problem;
    } catch (const InputError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(p.string()), std::string::npos) << m;
        EXPECT_NE(m.find(problem), std::string::npos) << "message: " << m << "\nexpected: " << problem;
    }
}

// writePrepared must throw an InputError naming the file and containing `problem`, and write nothing.
void expectWriteRefused(const fs::path& p, const PreparedVolume& prepared, const std::string& problem,
                        const PreparedWriteOptions& options = {}) {
    try {
        writePrepared(p, prepared, options);
        ADD_FAILURE() << "write of " << p << " succeeded; expected: " << problem;
    } catch (const InputError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(p.string()), std::string::npos) << m;
        EXPECT_NE(m.find(problem), std::string::npos) << "message: " << m << "\nexpected: " << problem;
    }
    EXPECT_FALSE(fs::exists(p));
}

// The good file's blocks: small, so that every chunk but the one-byte ones spans several (labels: 4 blocks).
constexpr std::size_t kSmallBlock = 512;

class IoPreparedFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir = test::scratchDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
        good = dir / "good.vprep";
        prepared = samplePrepared({13, 7, 5});
        writePrepared(good, prepared, {kPreparedZstdLevel, kSmallBlock});
        bad = dir / "bad.vprep";
    }
    // The good file, its header edited by `edit` (and its checksum updated), is rejected naming `problem`.
    void expectEditedHeaderRejected(const std::function<void(json&)>& edit, const std::string& problem) {
        Parts parts = split(good);
        edit(parts.header);
        join(bad, parts);
        expectRejected(bad, problem);
    }
    fs::path dir, good, bad;
    PreparedVolume prepared;
};

TEST_F(IoPreparedFile, RoundTripKeepsEveryChunkAndTheMetadata) {
    PreparedVolume r = readPrepared(good);
    const PreparedVolume& p = prepared;
    EXPECT_EQ(r.scalars.grid, p.scalars.grid);
    EXPECT_EQ(r.scalars.sourceType, ScalarType::Int16);
    EXPECT_EQ(r.scalars.values, p.scalars.values);
    EXPECT_EQ(r.scalars.source, p.meta.source);
    EXPECT_EQ(r.classification, p.classification);
    EXPECT_EQ(r.regions.dims, p.regions.dims);
    EXPECT_EQ(r.regions.count, p.regions.count);
    EXPECT_EQ(r.regions.label, p.regions.label);
    EXPECT_EQ(r.fields.dims, p.fields.dims);
    EXPECT_EQ(r.fields.pc, p.fields.pc);
    EXPECT_EQ(r.fields.acd, p.fields.acd);
    EXPECT_EQ(r.fields.eacd, p.fields.eacd);
    EXPECT_EQ(r.meta.source, p.meta.source);
    EXPECT_EQ(r.meta.classification, p.meta.classification);
    EXPECT_EQ(r.meta.segmentation.opacityThreshold, 0.01);
    EXPECT_EQ(r.meta.segmentation.angleThresholdDeg, 3.0);
    EXPECT_TRUE(r.meta.segmentation.useNormals);
    EXPECT_TRUE(r.meta.segmentation.trilinear);
    EXPECT_EQ(r.meta.distanceCap, kDistanceCap);
    EXPECT_EQ(r.meta.statistics, p.meta.statistics);
    EXPECT_EQ(r.meta.rayProbe, p.meta.rayProbe);
    EXPECT_LT(*std::min_element(r.scalars.values.begin(), r.scalars.values.end()), 0.0f);  // int16 below zero kept
}

// The scalars are stored in the volume's own type, each exactly, the ends of the type's range included; the chunks
// hold the scalar bytes, 4 label bytes and the field bytes per voxel, and the table, compressed.
TEST_F(IoPreparedFile, RoundTripOfEveryScalarType) {
    for (ScalarType type : kEveryScalarType) {
        SCOPED_TRACE(scalarTypeName(type));
        PreparedVolume p = samplePrepared({13, 7, 5}, type);
        std::vector<float>& v = p.scalars.values;
        switch (type) {
            case ScalarType::UInt8: v[0] = 0, v[1] = 255; break;
            case ScalarType::Int16: v[0] = -32768, v[1] = 32767; break;
            case ScalarType::UInt16: v[0] = 0, v[1] = 65535; break;
            case ScalarType::Float32:
                v[0] = std::numeric_limits<float>::lowest(), v[1] = std::numeric_limits<float>::denorm_min();
                break;
        }
        writePrepared(bad, p);
        const PreparedVolume r = readPrepared(bad);
        EXPECT_EQ(r.scalars.sourceType, type);
        EXPECT_EQ(r.scalars.values, v);
        EXPECT_EQ(r.scalars.grid, p.scalars.grid);
        EXPECT_EQ(r.classification, p.classification);

        const Parts parts = split(bad);
        EXPECT_EQ(parts.header["scalarType"], scalarTypeName(type));
        const json c = chunkEntry(parts.header, "scalars");
        EXPECT_EQ(c["type"], scalarTypeName(type));
        EXPECT_EQ(c["components"], 1);
        const std::size_t n = p.grid().voxels();
        EXPECT_EQ(c["bytes"], n * scalarBytes(type));
        std::vector<char> own(n * scalarBytes(type));  // the values in their own type, as the chunk holds them
        for (std::size_t i = 0; i < n; ++i) {
            char* at = own.data() + i * scalarBytes(type);
            switch (type) {
                case ScalarType::UInt8: *reinterpret_cast<uint8_t*>(at) = uint8_t(v[i]); break;
                case ScalarType::Int16: *reinterpret_cast<int16_t*>(at) = int16_t(v[i]); break;
                case ScalarType::UInt16: *reinterpret_cast<uint16_t*>(at) = uint16_t(v[i]); break;
                case ScalarType::Float32: *reinterpret_cast<float*>(at) = v[i]; break;
            }
        }
        EXPECT_EQ(chunkBytes(parts, "scalars"), own);
        // Read for a device upload alone: integer scalars in their own type, exactly the chunk's bytes, and no
        // floats, which a reader of floats is refused; float32 scalars as floats.
        const PreparedVolume narrow = readPrepared(bad, kFieldPC, {kAllOctants, true, false});
        if (type == ScalarType::Float32) {
            EXPECT_EQ(narrow.scalars.values, v);
            EXPECT_TRUE(narrow.scalars.stored.empty());
        } else {
            EXPECT_TRUE(narrow.scalars.values.empty());
            EXPECT_EQ(narrow.scalars.stored, std::vector<unsigned char>(own.begin(), own.end()));
            EXPECT_THROW(floatValues(narrow.scalars), std::logic_error);
        }
        EXPECT_EQ(narrow.scalars.sourceType, type);
        EXPECT_EQ(narrow.fields.pc, p.fields.pc);
        uint64_t bytes = 0, stored = 0;
        for (const json& chunk : parts.header["chunks"]) {
            bytes += chunk["bytes"].get<uint64_t>();
            for (const json& block : chunk["blocks"]) stored += block["compressedBytes"].get<uint64_t>();
        }
        EXPECT_EQ(bytes, n * (scalarBytes(type) + 4 + 1 + kOctants * (1 + 3)) + 37 * 16);
        EXPECT_EQ(parts.data.size(), stored);  // the blocks back to back, nothing else
        EXPECT_EQ(readPreparedHeader(bad).scalarType, type);
    }
}

// The table is stored as float32 r, g, b, sigma per entry and read back bit for bit; lo, step, the reference step
// and the flat gradient are doubles in the header and read back exactly.
TEST_F(IoPreparedFile, TableRoundTripsExactly) {
    const Parts parts = split(good);
    EXPECT_EQ(parts.header["transferTable"], (json{{"lo", -1024.1234567890123}, {"step", 0.1}, {"entries", 37}}));
    EXPECT_EQ(parts.header["flatGradient"].get<double>(), 1.0 / 3.0e5);
    const json c = chunkEntry(parts.header, "table");
    EXPECT_EQ(c["type"], "float32");
    EXPECT_EQ(c["components"], 4);
    EXPECT_EQ(c["bytes"], 37 * 16);
    float entry5[4];
    std::memcpy(entry5, chunkBytes(parts, "table").data() + 5 * 16, sizeof(entry5));
    EXPECT_EQ(entry5[0], prepared.classification.table.colour[5][0]);
    EXPECT_EQ(entry5[1], prepared.classification.table.colour[5][1]);
    EXPECT_EQ(entry5[2], prepared.classification.table.colour[5][2]);
    EXPECT_EQ(entry5[3], prepared.classification.table.sigma[5]);

    const ScalarClassification read = readPrepared(good, 0).classification;
    EXPECT_EQ(read, prepared.classification);
    EXPECT_EQ(read.table.sigma[1], std::numeric_limits<float>::denorm_min());

    PreparedVolume one = prepared;  // a table of one entry classifies every scalar alike
    one.classification.table.sigma = {2.5f};
    one.classification.table.colour = {{1, 0, 0.5f}};
    writePrepared(bad, one);
    EXPECT_EQ(readPrepared(bad, 0).classification, one.classification);
    EXPECT_EQ(readPreparedHeader(bad).tableEntries, 1u);
}

// The probe is stored among the statistics as before it had a type: files from either side read alike.
TEST_F(IoPreparedFile, KeepsTheRayProbeAmongTheStatistics) {
    const json probe = split(good).header["metadata"]["statistics"]["rayProbe"];
    EXPECT_EQ(probe["stepVoxels"], 0.5);
    EXPECT_EQ(probe["ert"], 0.99);
    EXPECT_EQ(probe["views"], (json{{"octant", 16}, {"quadrant", 6}, {"axis", 8}}));
    EXPECT_EQ(probe["casters"]["primitive"]["singleSamples"][26], 126);
    EXPECT_EQ(probe["casters"]["primitive"]["leaps"].size(), std::size_t(kProbeDirectionClasses));
    EXPECT_EQ(probe["casters"]["acd"]["leaps"][2], 0.5);
    EXPECT_FALSE(probe["casters"].contains("pc"));
    EXPECT_FALSE(probe["casters"].contains("eacd"));

    PreparedVolume none = prepared;
    none.meta.rayProbe.reset();
    writePrepared(bad, none);
    EXPECT_FALSE(split(bad).header["metadata"]["statistics"].contains("rayProbe"));
    EXPECT_FALSE(readPrepared(bad, 0).meta.rayProbe);
}

// An older volprep's probe (per-octant counts, no views) is no probe, and a caster's malformed counts no counts:
// the file still reads, and --caster auto chooses among what is left.
TEST_F(IoPreparedFile, ReadsAnOlderRayProbeAsNone) {
    Parts parts = split(good);
    json& probe = parts.header["metadata"]["statistics"]["rayProbe"];
    probe["casters"]["acd"]["singleSamples"] = std::vector<double>(kOctants, 1.0);
    join(bad, parts);
    std::optional<RayProbe> read = readPrepared(bad, 0).meta.rayProbe;
    ASSERT_TRUE(read);
    EXPECT_EQ(read->primitive, prepared.meta.rayProbe->primitive);
    EXPECT_FALSE(read->acd);

    for (const char* key : {"leaps", "singleSamples"})
        probe["casters"]["primitive"][key] = std::vector<double>(kOctants, 1.0);
    probe.erase("views");
    probe["raysPerSide"] = 32;
    join(bad, parts);
    const PreparedVolume older = readPrepared(bad, 0);
    EXPECT_FALSE(older.meta.rayProbe);
    EXPECT_FALSE(older.meta.statistics.contains("rayProbe"));
}

TEST_F(IoPreparedFile, ReadsTheHeaderAlone) {
    const PreparedHeader h = readPreparedHeader(good);
    EXPECT_EQ(h.grid, prepared.grid());
    EXPECT_EQ(h.scalarType, ScalarType::Int16);
    EXPECT_EQ(h.tableEntries, 37u);
    EXPECT_EQ(h.meta.source, prepared.meta.source);
    EXPECT_EQ(h.meta.segmentation, prepared.meta.segmentation);
    EXPECT_EQ(h.meta.statistics, prepared.meta.statistics);
    EXPECT_EQ(h.meta.rayProbe, prepared.meta.rayProbe);
    const std::size_t n = prepared.grid().voxels();
    EXPECT_EQ(h.fieldBytes.pc, n);
    EXPECT_EQ(h.fieldBytes.acd, kOctants * n);
    EXPECT_EQ(h.fieldBytes.eacd, kOctants * 3 * n);  // exact extents
    // Every chunk, in the order of the table, with its bytes in memory and in the file.
    const Parts goodParts = split(good);
    ASSERT_EQ(h.chunks.size(), goodParts.header["chunks"].size());
    uint64_t storedInAll = 0;
    for (std::size_t i = 0; i < h.chunks.size(); ++i) {
        const json& c = goodParts.header["chunks"][i];
        EXPECT_EQ(h.chunks[i].name, c["name"]);
        EXPECT_EQ(h.chunks[i].bytes, c["bytes"]);
        uint64_t stored = 0;
        for (const std::vector<char>& frame : storedBlocks(goodParts, h.chunks[i].name)) stored += frame.size();
        EXPECT_EQ(h.chunks[i].storedBytes, stored) << h.chunks[i].name;
        storedInAll += stored;
    }
    EXPECT_EQ(h.chunks[0].name, "scalars");
    EXPECT_EQ(h.chunks[2].bytes, 4 * n);  // labels
    EXPECT_EQ(storedInAll, goodParts.data.size());

    // A damaged chunk is not read; a damaged header is.
    std::vector<char> b = readBytes(good);
    b[dataStart(good)] ^= 0x5a;
    writeBytes(bad, b);
    EXPECT_EQ(readPreparedHeader(bad).grid, prepared.grid());
    Parts parts = split(good);
    parts.header["grid"]["dims"] = {13, 7, 6};
    join(bad, parts);
    EXPECT_THROW(readPreparedHeader(bad), InputError);
    parts = split(good);
    parts.header["transferTable"]["entries"] = 0;
    join(bad, parts);
    EXPECT_THROW(readPreparedHeader(bad), InputError);

    PreparedVolume pcOnly = prepared;
    pcOnly.fields.acd = {};
    pcOnly.fields.eacd = {};
    writePrepared(bad, pcOnly);
    const FieldBytes bytes = readPreparedHeader(bad).fieldBytes;
    EXPECT_EQ(bytes.pc, n);
    EXPECT_EQ(bytes.acd, 0u);
    EXPECT_EQ(bytes.eacd, 0u);
}

TEST_F(IoPreparedFile, ReadsOnlyWhatIsAskedFor) {
    PreparedVolume pc = readPrepared(good, kFieldPC);
    EXPECT_EQ(pc.fields.pc, prepared.fields.pc);
    EXPECT_FALSE(pc.fields.hasACD());
    EXPECT_FALSE(pc.fields.hasEACD());
    EXPECT_EQ(pc.scalars.values, prepared.scalars.values);
    EXPECT_EQ(pc.classification, prepared.classification);

    PreparedVolume eacd = readPrepared(good, kFieldEACD);
    EXPECT_FALSE(eacd.fields.hasPC());
    EXPECT_FALSE(eacd.fields.hasACD());
    EXPECT_EQ(eacd.fields.eacd, prepared.fields.eacd);

    PreparedVolume none = readPrepared(good, 0);
    EXPECT_FALSE(none.fields.hasPC() || none.fields.hasACD() || none.fields.hasEACD());
    EXPECT_EQ(none.regions.label, prepared.regions.label);
    EXPECT_EQ(none.scalars.values, prepared.scalars.values);
}

// A render's read: the octants its views' rays have, and no region labels (their count stays).
TEST_F(IoPreparedFile, ReadsTheOctantsAskedForWithoutTheRegions) {
    const unsigned octants = 0b10010010;  // 1, 4 and 7
    const PreparedVolume r = readPrepared(good, kFieldACD | kFieldEACD, {octants, false});
    for (int o = 0; o < kOctants; ++o) {
        SCOPED_TRACE(o);
        const bool asked = octants >> o & 1u;
        EXPECT_EQ(r.fields.acd[o], asked ? prepared.fields.acd[o] : std::vector<uint8_t>{});
        EXPECT_EQ(r.fields.eacd[o], asked ? prepared.fields.eacd[o] : ExtentField{});
    }
    EXPECT_TRUE(r.regions.label.empty());
    EXPECT_EQ(r.regions.count, prepared.regions.count);
    EXPECT_EQ(r.scalars.values, prepared.scalars.values);
    EXPECT_EQ(r.classification, prepared.classification);
}

TEST_F(IoPreparedFile, SkipsUnrequestedChunksEvenWhenTheyAreDamaged) {
    // Proof that a field not asked for is seeked past, not read: damage only the ACD chunks.
    std::vector<char> b = readBytes(good);
    uint64_t at = dataStart(good) + chunkEntry(split(good).header, "acd3")["offset"].get<uint64_t>();
    b[at] ^= 0x5a;
    writeBytes(bad, b);
    EXPECT_EQ(readPrepared(bad, kFieldPC | kFieldEACD).fields.eacd, prepared.fields.eacd);
    expectRejected(bad, "chunk 'acd3' checksum mismatch");
}

TEST_F(IoPreparedFile, OptionalChunksMayBeAbsentButNotWhenRequested) {
    PreparedVolume p = prepared;
    p.fields = {};
    p.fields.dims = p.grid().dims;
    p.fields.pc = prepared.fields.pc;
    writePrepared(bad, p);
    PreparedVolume r = readPrepared(bad, kFieldPC);
    EXPECT_EQ(r.fields.pc, p.fields.pc);
    expectRejected(bad, "has no ACD distance field", kFieldACD);
    expectRejected(bad, "has no EACD distance field", kFieldEACD);

    p.fields.pc.clear();
    writePrepared(bad, p);
    expectRejected(bad, "has no PC distance field", kFieldPC);
    EXPECT_EQ(readPrepared(bad, 0).scalars.values, prepared.scalars.values);
}

TEST_F(IoPreparedFile, RejectsAFileWithoutARequiredChunk) {
    for (const char* name : {"scalars", "table", "labels"}) {
        SCOPED_TRACE(name);
        expectEditedHeaderRejected(
            [&](json& h) {
                json& chunks = h["chunks"];
                for (std::size_t i = 0; i < chunks.size(); ++i)
                    if (chunks[i]["name"] == name) chunks.erase(i);
            },
            std::string("has no '") + name + "' chunk");
    }
}

TEST_F(IoPreparedFile, RejectsAMissingFile) { expectRejected(dir / "absent.vprep", "no such file"); }

TEST_F(IoPreparedFile, RejectsAFolder) { expectRejected(dir, "not a regular file"); }

TEST_F(IoPreparedFile, RejectsAForeignFile) {
    std::vector<char> b = readBytes(good);
    b[0] = 'W';
    writeBytes(bad, b);
    expectRejected(bad, "not a prepared file");
    writeBytes(bad, {'h', 'i', '\n'});
    expectRejected(bad, "not a prepared file");
}

TEST_F(IoPreparedFile, CodedExtentsAreStoredCodedAndReadBackAsTheSameBoxes) {
    auto arrayBytes = [](const json& header) {  // of every chunk, uncompressed
        uint64_t bytes = 0;
        for (const json& c : header["chunks"]) bytes += c["bytes"].get<uint64_t>();
        return bytes;
    };
    const uint64_t exactBytes = arrayBytes(split(good).header);
    const std::size_t voxels = prepared.grid().voxels();
    for (ExtentCode code : {ExtentCode::Log16, ExtentCode::Joint8}) {
        SCOPED_TRACE(extentCodeName(code));
        PreparedVolume p = prepared;
        quantiseEACD(p.fields, code);
        writePrepared(bad, p);
        const json header = split(bad).header;
        EXPECT_EQ(header["eacdCode"], extentCodeName(code));
        const json c = chunkEntry(header, "eacd5");
        EXPECT_EQ(c["type"], code == ExtentCode::Log16 ? "uint16" : "uint8");
        EXPECT_EQ(c["components"], 1);
        EXPECT_EQ(c["bytes"], voxels * extentCodeBytes(code));
        EXPECT_EQ(arrayBytes(header), exactBytes - kOctants * voxels * (3 - extentCodeBytes(code)));

        const PreparedVolume r = readPrepared(bad);
        EXPECT_EQ(r.fields.eacdCode(), code);
        EXPECT_EQ(r.fields.eacd, p.fields.eacd);
        EXPECT_EQ(r.fields.acd, p.fields.acd);
        EXPECT_FALSE(readPrepared(bad, kFieldPC).fields.hasEACD());
    }
    EXPECT_EQ(readPrepared(good).fields.eacdCode(), ExtentCode::Exact);

    // The octants must share one code: the header names one.
    PreparedVolume mixed = prepared;
    quantiseEACD(mixed.fields, ExtentCode::Log16);
    mixed.fields.eacd[6] = prepared.fields.eacd[6];
    EXPECT_THROW(writePrepared(bad, mixed), InputError);
}

TEST_F(IoPreparedFile, RejectsAnUnknownOrInconsistentExtentCode) {
    expectEditedHeaderRejected([](json& h) { h["eacdCode"] = "log12"; },
                               "bad header: 'eacdCode': unknown EACD code 'log12' (expected exact, log16 or joint8)");
    expectEditedHeaderRejected([](json& h) { h.erase("eacdCode"); }, "bad header: missing or invalid 'eacdCode'");
    expectEditedHeaderRejected([](json& h) { h["eacdCode"] = "joint8"; },  // the chunks hold 3 exact bytes per voxel
                               "chunk 'eacd0' should be 1 x uint8");
}

TEST_F(IoPreparedFile, RejectsEarlierVersions) {
    // Version 1 stored EACD as 3 bytes per octant with no eacdCode, version 2 the classified volume (sigma, colour,
    // normal) instead of the scalars and the table, version 3 every chunk uncompressed, version 4 no label map,
    // version 5 the chunks' bytes not coded over slices: refused with the way out, not misread.
    for (uint32_t v : {1u, 2u, 3u, 4u, 5u}) {
        std::vector<char> b = readBytes(good);
        std::memcpy(b.data() + 8, &v, 4);
        writeBytes(bad, b);
        expectRejected(bad, "prepared format version " + std::to_string(v) +
                                ", this build reads version 6 (run volprep again)");
    }
    // A version 3 file as it was: the chunks raw, each with the CRC-32 of its bytes, no compression in the header.
    Parts parts = split(good);
    std::vector<char> data;
    for (json& c : parts.header["chunks"]) {
        const std::vector<char> plain = chunkBytes(split(good), c["name"].get<std::string>());
        c.erase("blocks");
        c["offset"] = data.size();
        c["crc32"] = crcOf(plain);
        data.insert(data.end(), plain.begin(), plain.end());
    }
    parts.header.erase("compression");
    parts.data = data;
    const uint32_t three = 3;
    std::memcpy(parts.preamble.data() + 8, &three, 4);
    join(bad, parts);
    expectRejected(bad, "prepared format version 3, this build reads version 6 (run volprep again)");
    EXPECT_THROW(readPreparedHeader(bad), InputError);
}

TEST_F(IoPreparedFile, RejectsAnotherVersion) {
    std::vector<char> b = readBytes(good);
    uint32_t v = kPreparedFormatVersion + 1;
    std::memcpy(b.data() + 8, &v, 4);
    writeBytes(bad, b);
    expectRejected(bad, "prepared format version " + std::to_string(v) + ", this build reads version " +
                            std::to_string(kPreparedFormatVersion));
}

TEST_F(IoPreparedFile, RejectsAnAbsurdHeaderLength) {
    std::vector<char> b = readBytes(good);
    const uint64_t len = (uint64_t(1) << 30) + 1;
    std::memcpy(b.data() + 12, &len, 8);
    writeBytes(bad, b);
    expectRejected(bad, "bad header length 1073741825");
}

TEST_F(IoPreparedFile, RejectsATruncatedFileAtEveryPart) {
    std::vector<char> b = readBytes(good);
    uint64_t data = dataStart(good);
    json header = split(good).header;
    uint64_t table = data + chunkEntry(header, "table")["offset"].get<uint64_t>();
    uint64_t labels = data + chunkEntry(header, "labels")["offset"].get<uint64_t>();
    struct Cut {
        std::size_t size;
        std::string problem;
    };
    const uint64_t labelsBlock1 = labels + chunkEntry(header, "labels")["blocks"][0]["compressedBytes"].get<uint64_t>();
    for (const Cut& cut : std::vector<Cut>{{0, "not a prepared file (only 0 bytes"},
                                           {7, "not a prepared file (only 7 bytes"},
                                           {19, "not a prepared file (only 19 bytes"},
                                           {20, "truncated header"},
                                           {20 + 10, "truncated header"},
                                           {data - 2, "truncated header"},
                                           {data, "truncated: chunk 'scalars'"},
                                           {table + 5, "truncated: chunk 'table'"},
                                           {labels + 3, "truncated: chunk 'labels'"},
                                           {labelsBlock1 + 1, "truncated: chunk 'labels'"},  // in its second block
                                           {b.size() - 1, "truncated: chunk 'eacd7'"}}) {
        SCOPED_TRACE(cut.size);
        writeBytes(bad, std::vector<char>(b.begin(), b.begin() + std::ptrdiff_t(cut.size)));
        expectRejected(bad, cut.problem);
    }
}

TEST_F(IoPreparedFile, RejectsAFlippedByteInAChunk) {
    const Parts parts = split(good);
    for (const char* name : {"scalars", "table", "labels", "pc", "acd0", "eacd7"}) {
        SCOPED_TRACE(name);
        std::vector<char> b = readBytes(good);
        uint64_t stored = 0;
        for (const std::vector<char>& frame : storedBlocks(parts, name)) stored += frame.size();
        b[dataStart(good) + chunkEntry(parts.header, name)["offset"].get<uint64_t>() + stored / 2] ^= 0x01;
        writeBytes(bad, b);
        expectRejected(bad, std::string("chunk '") + name + "' checksum mismatch in block ");
    }
}

// Every chunk is split into blocks of the header's size (the last one holds the rest), each block one zstd frame that
// states its size, with the CRC-32 of the frame; the chunks' blocks lie back to back in the order of the table.
TEST_F(IoPreparedFile, WritesEveryChunkAsIndependentZstdBlocks) {
    const Parts parts = split(good);
    EXPECT_EQ(parts.header["compression"],
              (json{{"codec", "zstd"}, {"filter", "sliceDelta"}, {"level", kPreparedZstdLevel},
                    {"blockBytes", kSmallBlock}}));
    uint64_t offset = 0;
    for (const json& c : parts.header["chunks"]) {
        const std::string name = c["name"].get<std::string>();
        SCOPED_TRACE(name);
        const uint64_t bytes = c["bytes"].get<uint64_t>();
        EXPECT_FALSE(c.contains("crc32"));  // version 3's checksum of the whole chunk: the blocks have their own
        EXPECT_EQ(c["offset"].get<uint64_t>(), offset);
        ASSERT_EQ(c["blocks"].size(), (bytes + kSmallBlock - 1) / kSmallBlock);
        const std::vector<std::vector<char>> frames = storedBlocks(parts, name);
        for (std::size_t k = 0; k < frames.size(); ++k) {
            EXPECT_EQ(c["blocks"][k]["crc32"].get<uint32_t>(), crcOf(frames[k]));
            EXPECT_EQ(ZSTD_findFrameCompressedSize(frames[k].data(), frames[k].size()), frames[k].size());
            EXPECT_EQ(ZSTD_getFrameContentSize(frames[k].data(), frames[k].size()),
                      std::min<uint64_t>(kSmallBlock, bytes - k * kSmallBlock));
            offset += frames[k].size();
        }
    }
    EXPECT_EQ(offset, parts.data.size());
    EXPECT_EQ(chunkEntry(parts.header, "labels")["blocks"].size(), 4u);  // 1820 bytes
    EXPECT_EQ(chunkBytes(parts, "labels"), bytesOf(prepared.regions.label));
    EXPECT_EQ(chunkBytes(parts, "pc"), bytesOf(prepared.fields.pc));
    EXPECT_EQ(chunkBytes(parts, "acd6"), bytesOf(prepared.fields.acd[6]));
    const std::vector<char> eacd = chunkBytes(parts, "eacd3");
    EXPECT_EQ(eacd, std::vector<char>(reinterpret_cast<const char*>(prepared.fields.eacd[3].data()),
                                      reinterpret_cast<const char*>(prepared.fields.eacd[3].data()) + eacd.size()));
    EXPECT_EQ(eacd.size(), 3 * prepared.grid().voxels());

    // The chunks are far smaller than the arrays (the sample's fields repeat a few values).
    writePrepared(bad, prepared);
    const Parts defaults = split(bad);
    EXPECT_EQ(defaults.header["compression"],
              (json{{"codec", "zstd"}, {"filter", "sliceDelta"}, {"level", kPreparedZstdLevel},
                    {"blockBytes", kPreparedBlockBytes}}));
    for (const json& c : defaults.header["chunks"]) EXPECT_EQ(c["blocks"].size(), 1u) << c["name"];
    EXPECT_LT(chunkEntry(defaults.header, "acd0")["blocks"][0]["compressedBytes"].get<uint64_t>(),
              prepared.grid().voxels());
}

// Any block size (1 byte to a whole chunk) and any zstd level give the same arrays back, bit for bit, with every
// EACD code.
TEST_F(IoPreparedFile, RoundTripsAtEveryBlockSizeAndLevel) {
    for (ExtentCode code : {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8}) {
        PreparedVolume p =
            samplePrepared({13, 7, 5}, code == ExtentCode::Joint8 ? ScalarType::Float32 : ScalarType::UInt16);
        quantiseEACD(p.fields, code);
        struct Options {
            std::size_t block;
            int level;
        };
        for (const Options& o : std::vector<Options>{{7, 1}, {100, 1}, {1000, 1}, {kPreparedBlockBytes, 1},
                                                     {1000, ZSTD_minCLevel()}, {1000, -5}, {1000, 3}, {1000, 19}}) {
            const std::size_t block = o.block;
            const int level = o.level;
            {
                SCOPED_TRACE(std::string(extentCodeName(code)) + ", blocks of " + std::to_string(block) +
                             " bytes, level " + std::to_string(level));
                writePrepared(bad, p, {level, block});
                const PreparedVolume r = readPrepared(bad);
                EXPECT_EQ(r.scalars.values, p.scalars.values);
                EXPECT_EQ(r.scalars.sourceType, p.scalars.sourceType);
                EXPECT_EQ(r.classification, p.classification);
                EXPECT_EQ(r.regions.label, p.regions.label);
                EXPECT_EQ(r.fields.pc, p.fields.pc);
                EXPECT_EQ(r.fields.acd, p.fields.acd);
                EXPECT_EQ(r.fields.eacdCode(), code);
                EXPECT_EQ(r.fields.eacd, p.fields.eacd);
                EXPECT_EQ(r.meta.statistics, p.meta.statistics);
                const json header = split(bad).header;
                EXPECT_EQ(header["compression"]["level"], level);
                EXPECT_EQ(chunkEntry(header, "labels")["blocks"].size(), (4 * 455 + block - 1) / block);
            }
        }
    }
}

// At the default block size: chunks of several blocks, read in parallel into one array, and a damaged block named.
TEST_F(IoPreparedFile, ReadsChunksOfSeveralBlocksAtTheDefaultSize) {
    const Vec3i dims{128, 128, 72};  // 1179648 voxels: 4.5 MiB of float scalars, 4.5 MiB of labels
    PreparedVolume p;
    p.scalars.grid.dims = dims;
    p.scalars.sourceType = ScalarType::Float32;
    p.classification = sampleClassification();
    p.regions.dims = dims;
    p.regions.count = 5000;
    const std::size_t n = p.grid().voxels();
    for (std::size_t i = 0; i < n; ++i) {
        p.scalars.values.push_back(float((i * 2654435761u) % 100003) * 0.125f - 17);
        p.regions.label.push_back(uint32_t(i / 300 % 5000));
    }
    writePrepared(bad, p);
    const PreparedVolume r = readPrepared(bad, 0);
    EXPECT_EQ(r.scalars.values, p.scalars.values);
    EXPECT_EQ(r.regions.label, p.regions.label);
    const Parts parts = split(bad);
    for (const char* name : {"scalars", "labels"}) {
        SCOPED_TRACE(name);
        const json c = chunkEntry(parts.header, name);
        EXPECT_EQ(c["bytes"], 4 * n);
        ASSERT_EQ(c["blocks"].size(), 2u);
        const std::vector<std::vector<char>> frames = storedBlocks(parts, name);
        EXPECT_EQ(ZSTD_getFrameContentSize(frames[0].data(), frames[0].size()), kPreparedBlockBytes);
        EXPECT_EQ(ZSTD_getFrameContentSize(frames[1].data(), frames[1].size()), 4 * n - kPreparedBlockBytes);
    }
    std::vector<char> b = readBytes(bad);
    const json labels = chunkEntry(parts.header, "labels");
    b[dataStart(bad) + labels["offset"].get<uint64_t>() +
      labels["blocks"][0]["compressedBytes"].get<uint64_t>() + 7] ^= 4;
    const fs::path damaged = dir / "damaged.vprep";
    writeBytes(damaged, b);
    expectRejected(damaged, "chunk 'labels' checksum mismatch in block 1 of 2 (file is corrupted)", 0);
}

// A block that is not what it claims: caught by its CRC-32, or, where the CRC-32 was made to match, by zstd. Either
// way the message names the chunk and the block, and the first bad block is the one named.
TEST_F(IoPreparedFile, RejectsACorruptedBlock) {
    std::vector<char> b = readBytes(good);
    const Parts parts = split(good);
    const json labels = chunkEntry(parts.header, "labels");
    const std::vector<std::vector<char>> frames = storedBlocks(parts, "labels");
    ASSERT_EQ(frames.size(), 4u);
    uint64_t block2 = dataStart(good) + labels["offset"].get<uint64_t>() + frames[0].size() + frames[1].size();
    b[block2 + frames[2].size() / 2] ^= 0x10;
    b[block2 + frames[2].size() + 3] ^= 0x10;  // block 3 too: block 2 is named
    writeBytes(bad, b);
    expectRejected(bad, "chunk 'labels' checksum mismatch in block 2 of 4 (file is corrupted)");

    // Matching CRC-32s, contents zstd refuses.
    auto withBlock1 = [&](const std::vector<char>& frame, const std::string& problem) {
        SCOPED_TRACE(problem);
        Parts edited = split(good);
        std::vector<std::vector<char>> blocks = frames;
        blocks[1] = frame;
        replaceBlocks(edited, "labels", blocks);
        join(bad, edited);
        expectRejected(bad, problem);
    };
    withBlock1(std::vector<char>(20, 'x'), "chunk 'labels' block 1 of 4 cannot be decompressed (zstd: ");
    withBlock1(std::vector<char>(frames[1].begin(), frames[1].end() - 1),  // the frame cut short
               "chunk 'labels' block 1 of 4 cannot be decompressed (zstd: ");
    // A frame whose header is right (RFC 8878: magic, a descriptor for one segment with a 4-byte size, 512), but
    // whose one block is compressed garbage.
    std::vector<char> garbage = {'\x28', '\xb5', '\x2f', '\xfd', '\xa0', 0, 2, 0, 0};
    const uint32_t blockHeader = 1 | (2 << 1) | (16 << 3);  // last block, compressed, 16 bytes
    garbage.insert(garbage.end(), {char(blockHeader & 0xff), char(blockHeader >> 8), char(blockHeader >> 16)});
    garbage.insert(garbage.end(), 16, char(0xff));
    ASSERT_EQ(ZSTD_findFrameCompressedSize(garbage.data(), garbage.size()), garbage.size());
    withBlock1(garbage, "chunk 'labels' block 1 of 4 cannot be decompressed (zstd: ");
    withBlock1(compress(std::vector<char>(kSmallBlock, 0).data(), kSmallBlock, 1, false),
               "chunk 'labels' block 1 of 4 does not state its decompressed size");
}

// Block sizes that lie: a block's stated compressed size against its frame, a frame's stated size against the
// block's, the number of blocks against the chunk's size.
TEST_F(IoPreparedFile, RejectsBlocksWhoseSizesLie) {
    const Parts parts = split(good);
    const std::vector<std::vector<char>> frames = storedBlocks(parts, "labels");
    const std::vector<char> plain = chunkBytes(parts, "labels");
    auto withBlocks = [&](const std::vector<std::vector<char>>& blocks, const std::string& problem) {
        SCOPED_TRACE(problem);
        Parts edited = split(good);
        replaceBlocks(edited, "labels", blocks);
        join(bad, edited);
        expectRejected(bad, problem);
    };
    // Block 0 said to be a byte longer (taking block 1's first byte), its CRC-32 made to match.
    std::vector<std::vector<char>> blocks = frames;
    blocks[0].push_back(blocks[1].front());
    blocks[1].erase(blocks[1].begin());
    withBlocks(blocks, "chunk 'labels' block 0 of 4 holds " + std::to_string(frames[0].size() + 1) +
                           " bytes but its zstd frame takes " + std::to_string(frames[0].size()));
    // Frames of the wrong size: fewer bytes than the block holds, more than the last block holds.
    blocks = frames;
    blocks[1] = compress(plain.data() + kSmallBlock, 500);
    withBlocks(blocks, "chunk 'labels' block 1 of 4 decompresses to 500 bytes but should hold 512");
    blocks = frames;
    blocks[3] = compress(plain.data(), kSmallBlock);
    withBlocks(blocks, "chunk 'labels' block 3 of 4 decompresses to 512 bytes but should hold 284");
    // One block too few or too many for 1820 bytes in blocks of 512.
    withBlocks({frames[0], frames[1], frames[2]},
               "chunk 'labels' has 3 blocks but 1820 bytes in blocks of 512 bytes make 4");
    withBlocks({frames[0], frames[1], frames[2], frames[3], frames[3]},
               "chunk 'labels' has 5 blocks but 1820 bytes in blocks of 512 bytes make 4");

    // Stated compressed sizes no zstd frame of the block can have, refused before anything is read.
    const std::string bound = std::to_string(ZSTD_compressBound(kSmallBlock));
    for (uint64_t stored : {uint64_t(0), ZSTD_compressBound(kSmallBlock) + 1, uint64_t(1) << 40}) {
        SCOPED_TRACE(stored);
        expectEditedHeaderRejected(
            [&](json& h) { chunkEntryToEdit(h, "labels")["blocks"][1]["compressedBytes"] = stored; },
            "chunk 'labels' block 1 of 4 holds " + std::to_string(stored) +
                " compressed bytes (a zstd frame of 512 bytes takes 1 to " + bound + ")");
    }
    // Blocks said to reach past the end of the file.
    expectEditedHeaderRejected(
        [&](json& h) {
            json& last = chunkEntryToEdit(h, "eacd7")["blocks"].back();
            last["compressedBytes"] = last["compressedBytes"].get<uint64_t>() + 1;
        },
        "truncated: chunk 'eacd7' ends at byte ");
    expectEditedHeaderRejected([](json& h) { chunkEntryToEdit(h, "labels")["blocks"] = 5; },
                               "chunk 'labels' has no blocks but 1820 bytes in blocks of 512 bytes make 4");
    expectEditedHeaderRejected([](json& h) { chunkEntryToEdit(h, "labels").erase("blocks"); },
                               "bad header: missing or invalid 'blocks'");
    expectEditedHeaderRejected([](json& h) { chunkEntryToEdit(h, "labels")["blocks"][2] = 7; },
                               "bad header: missing or invalid 'compressedBytes'");
    // Another block size: the chunks' block counts no longer agree.
    expectEditedHeaderRejected([](json& h) { h["compression"]["blockBytes"] = 1024; },
                               "chunk 'scalars' has 2 blocks but 910 bytes in blocks of 1024 bytes make 1");
}

TEST_F(IoPreparedFile, RejectsABadCompressionHeader) {
    const std::string blockBytes = "bad header: 'compression.blockBytes' must be an integer from 1 to 1073741824";
    for (const json& value : {json(0), json((uint64_t(1) << 30) + 1), json(-512), json(512.5), json("512")}) {
        SCOPED_TRACE(value.dump());
        expectEditedHeaderRejected([&](json& h) { h["compression"]["blockBytes"] = value; }, blockBytes);
    }
    expectEditedHeaderRejected([](json& h) { h["compression"].erase("blockBytes"); },
                               "bad header: missing or invalid 'blockBytes'");
    expectEditedHeaderRejected([](json& h) { h["compression"]["codec"] = "lz4"; },
                               "bad header: 'compression.codec': unknown codec 'lz4' (expected zstd)");
    expectEditedHeaderRejected([](json& h) { h["compression"]["codec"] = 1; },
                               "bad header: missing or invalid 'codec'");
    expectEditedHeaderRejected([](json& h) { h["compression"]["filter"] = "shuffle"; },
                               "bad header: 'compression.filter': unknown filter 'shuffle' (expected sliceDelta)");
    expectEditedHeaderRejected([](json& h) { h["compression"].erase("filter"); },
                               "bad header: missing or invalid 'filter'");
    expectEditedHeaderRejected([](json& h) { h["compression"] = "zstd"; },
                               "bad header: missing or invalid 'compression'");
    expectEditedHeaderRejected([](json& h) { h.erase("compression"); }, "bad header: missing or invalid 'compression'");
    // The level is informative: the reader needs none.
    Parts parts = split(good);
    parts.header["compression"].erase("level");
    join(bad, parts);
    EXPECT_EQ(readPrepared(bad).regions.label, prepared.regions.label);
}

TEST_F(IoPreparedFile, RejectsAnEditedHeader) {
    std::vector<char> b = readBytes(good);
    std::string text(b.begin() + 20, b.begin() + std::ptrdiff_t(dataStart(good) - 4));
    std::size_t at = text.find("\"referenceStep\": 0.5");
    ASSERT_NE(at, std::string::npos) << text;
    b[20 + at + std::strlen("\"referenceStep\": 0.")] = '7';  // same length, checksum not updated
    writeBytes(bad, b);
    expectRejected(bad, "header checksum mismatch");
}

TEST_F(IoPreparedFile, RejectsDimsInconsistentWithTheChunks) {
    expectEditedHeaderRejected([](json& h) { h["grid"]["dims"] = {13, 7, 6}; },
                               "chunk 'scalars' holds 910 bytes but grid 13x7x6 needs 1092");
}

TEST_F(IoPreparedFile, RejectsAbsurdDims) {
    for (json dims : {json{100000, 100000, 100000}, json{60000, 60000, 60000}, json{0, 7, 5}, json{13, -7, 5}}) {
        SCOPED_TRACE(dims.dump());
        expectEditedHeaderRejected([&](json& h) { h["grid"]["dims"] = dims; }, "absurd grid dims");
    }
}

TEST_F(IoPreparedFile, RejectsABadSpacingOrOrigin) {
    expectEditedHeaderRejected([](json& h) { h["grid"]["spacing"] = {0.5, 0, 2}; },
                               "bad header: 'spacing' must be positive and 'origin' finite");
    expectEditedHeaderRejected([](json& h) { h["grid"]["spacing"] = {0.5, -1, 2}; },
                               "bad header: 'spacing' must be positive and 'origin' finite");
    expectEditedHeaderRejected([](json& h) { h["grid"]["spacing"] = {1e307, 1e307, 1e307}; },
                               "bad header: 'spacing' x dims overflows");
    expectEditedHeaderRejected([](json& h) { h["grid"]["origin"] = {0, nullptr, 0}; },
                               "bad header: missing or invalid 'origin'");
    expectEditedHeaderRejected([](json& h) { h["grid"]["spacing"] = {1, 1}; }, "bad header: 'spacing' needs 3 numbers");
}

TEST_F(IoPreparedFile, RejectsABadChunkTable) {
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["type"] = "float64"; },
                               "chunk 'scalars' should be 1 x int16");
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["type"] = "uint8"; },
                               "chunk 'table' should be 4 x float32");
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["components"] = 3; },
                               "chunk 'table' should be 4 x float32");
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["name"] = "scalars"; }, "chunk 'scalars' appears twice");
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["name"] = "opacity"; }, "unknown chunk 'opacity'");
    // The classified volume of version 2 is no chunk of versions 3 and 4.
    for (const char* name : {"sigma", "colour", "normal"}) {
        SCOPED_TRACE(name);
        expectEditedHeaderRejected([&](json& h) { h["chunks"][0]["name"] = name; },
                                   std::string("unknown chunk '") + name + "'");
    }
    expectEditedHeaderRejected([](json& h) { h.erase("grid"); }, "bad header: missing or invalid 'grid'");
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["offset"] = uint64_t(1) << 40; },
                               "truncated: chunk 'scalars'");
}

TEST_F(IoPreparedFile, RejectsATableChunkOfTheWrongSize) {
    // The table chunk is sized by the header's entry count, not by the grid.
    expectEditedHeaderRejected([](json& h) { h["transferTable"]["entries"] = 36; },
                               "chunk 'table' holds 592 bytes but a transfer table of 36 entries needs 576");
    expectEditedHeaderRejected([](json& h) { h["transferTable"]["entries"] = 455; },  // the voxel count
                               "chunk 'table' holds 592 bytes but a transfer table of 455 entries needs 7280");
}

TEST_F(IoPreparedFile, RejectsAnUnknownScalarType) {
    for (const char* name : {"int32", "float", "UINT8", ""}) {
        SCOPED_TRACE(name);
        expectEditedHeaderRejected([&](json& h) { h["scalarType"] = name; },
                                   std::string("bad header: 'scalarType': unknown scalar type '") + name +
                                       "' (expected uint8, int16, uint16 or float32)");
    }
    expectEditedHeaderRejected([](json& h) { h.erase("scalarType"); }, "bad header: missing or invalid 'scalarType'");
    expectEditedHeaderRejected([](json& h) { h["scalarType"] = 2; }, "bad header: missing or invalid 'scalarType'");
    // A known type that the chunk does not hold.
    expectEditedHeaderRejected([](json& h) { h["scalarType"] = "uint8"; }, "chunk 'scalars' should be 1 x uint8");
    expectEditedHeaderRejected([](json& h) { h["scalarType"] = "float32"; }, "chunk 'scalars' should be 1 x float32");
}

TEST_F(IoPreparedFile, RejectsBadClassificationNumbers) {
    struct Case {
        std::string key;  // "transferTable.KEY" for a key of the table
        json value;       // null: the key removed
        std::string problem;
    };
    const std::string flat = "bad header: 'flatGradient' must be a finite number >= 0";
    const std::string step = "bad header: 'referenceStep' must be a finite number > 0";
    const std::string lo = "bad header: 'transferTable.lo' must be a finite number";
    const std::string tableStep = "bad header: 'transferTable.step' must be a finite number > 0";
    const std::string entries = "bad header: 'transferTable.entries' must be an integer from 1 to 1048576";
    for (const Case& c : std::vector<Case>{{"flatGradient", -0.5, flat},
                                           {"flatGradient", "0", flat},
                                           {"flatGradient", true, flat},
                                           {"flatGradient", nullptr, "bad header: missing or invalid 'flatGradient'"},
                                           {"referenceStep", 0, step},
                                           {"referenceStep", -1.5, step},
                                           {"referenceStep", "1", step},
                                           {"referenceStep", nullptr, "bad header: missing or invalid 'referenceStep'"},
                                           {"transferTable", 5, "bad header: missing or invalid 'transferTable'"},
                                           {"transferTable", nullptr, "bad header: missing or invalid 'transferTable'"},
                                           {"transferTable.lo", "x", lo},
                                           {"transferTable.lo", json::array({1}), lo},
                                           {"transferTable.lo", nullptr, "bad header: missing or invalid 'lo'"},
                                           {"transferTable.step", 0, tableStep},
                                           {"transferTable.step", -0.1, tableStep},
                                           {"transferTable.step", "0.1", tableStep},
                                           {"transferTable.step", nullptr, "bad header: missing or invalid 'step'"},
                                           {"transferTable.entries", 0, entries},
                                           {"transferTable.entries", (1 << 20) + 1, entries},
                                           {"transferTable.entries", 37.5, entries},
                                           {"transferTable.entries", -37, entries},
                                           {"transferTable.entries", "37", entries},
                                           {"transferTable.entries", nullptr,
                                            "bad header: missing or invalid 'entries'"}}) {
        SCOPED_TRACE(c.key + " = " + c.value.dump());
        expectEditedHeaderRejected(
            [&](json& h) {
                const bool inTable = c.key.rfind("transferTable.", 0) == 0;
                json& object = inTable ? h["transferTable"] : h;
                const std::string key = inTable ? c.key.substr(std::strlen("transferTable.")) : c.key;
                if (c.value.is_null())
                    object.erase(key);
                else
                    object[key] = c.value;
            },
            c.problem);
    }
    // Finite lo and step whose table ends past the largest double.
    expectEditedHeaderRejected(
        [](json& h) {
            h["transferTable"]["lo"] = 1e308;
            h["transferTable"]["step"] = 1e307;
        },
        "bad header: 'transferTable' ends at a scalar that is not finite");
}

TEST_F(IoPreparedFile, RejectsTableEntriesThatCannotBeRendered) {
    Parts parts = split(good);
    const float negative = -1;
    patchChunk(parts, "table", 3 * 16 + 12, &negative, 4);  // entry 3's sigma
    join(bad, parts);
    expectRejected(bad, "transfer table entry 3 has sigma -1 (must be finite and >= 0)");

    parts = split(good);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    patchChunk(parts, "table", 5 * 16 + 4, &nan, 4);  // entry 5's green
    join(bad, parts);
    expectRejected(bad, "transfer table entry 5 has a colour that is not finite");
}

TEST_F(IoPreparedFile, RejectsNonFiniteFloatScalars) {
    writePrepared(bad, samplePrepared({13, 7, 5}, ScalarType::Float32));
    for (float v : {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity()}) {
        Parts parts = split(bad);
        patchChunk(parts, "scalars", 17 * 4, &v, 4);
        const fs::path patched = dir / "patched.vprep";
        join(patched, parts);
        expectRejected(patched, std::string("scalars hold ") + (std::isnan(v) ? "nan" : "-inf") +
                                    " at voxel 17 (must be finite)");
    }
}

TEST_F(IoPreparedFile, RejectsNumbersThatDoNotFit) {
    for (const auto& entry : std::vector<std::pair<std::string, json>>{
             {"offset", -5}, {"offset", 1e30}, {"bytes", 12.5}, {"components", "3"}}) {
        const std::string& key = entry.first;  // a named reference: clang 14 cannot capture structured bindings
        const json& value = entry.second;
        SCOPED_TRACE(key + " = " + value.dump());
        expectEditedHeaderRejected([&](json& h) { h["chunks"][2][key] = value; },
                                   "bad header: '" + key + "' must be an integer");
    }
    for (const auto& entry : std::vector<std::pair<std::string, json>>{
             {"crc32", uint64_t(1) << 40}, {"crc32", -1}, {"compressedBytes", 12.5}, {"compressedBytes", "9"}}) {
        const std::string& key = entry.first;
        const json& value = entry.second;
        SCOPED_TRACE(key + " = " + value.dump());
        expectEditedHeaderRejected([&](json& h) { h["chunks"][2]["blocks"][1][key] = value; },
                                   "bad header: '" + key + "' must be an integer");
    }
    expectEditedHeaderRejected([](json& h) { h["grid"]["dims"] = {13, 7.5, 5}; }, "absurd grid dims 13x7.5x5");
    expectEditedHeaderRejected([](json& h) { h["regionCount"] = -1; },
                               "bad header: 'regionCount' must be an integer from 0 to 4294967295");
    expectEditedHeaderRejected([](json& h) { h["metadata"]["distanceCap"] = 256; },
                               "bad header: 'distanceCap' must be an integer from 0 to 255");
}

TEST_F(IoPreparedFile, RejectsLabelsBeyondTheRegionCount) {
    expectEditedHeaderRejected([](json& h) { h["regionCount"] = 15; },  // the labels go up to 15
                               "labels hold region id 15 but regionCount is 15");
}

TEST_F(IoPreparedFile, RejectsHeaderThatIsNotJson) {
    std::vector<char> b = readBytes(good);
    uint64_t len;
    std::memcpy(&len, b.data() + 12, 8);
    b[20] = '#';
    uint32_t crc = uint32_t(crc32_z(0, reinterpret_cast<const Bytef*>(b.data() + 20), len));
    std::memcpy(b.data() + 20 + len, &crc, 4);
    writeBytes(bad, b);
    expectRejected(bad, "bad header: ");
}

TEST_F(IoPreparedFile, RefusesToWriteScalarsTheTypeCannotHold) {
    struct Case {
        ScalarType type;
        float value;
        std::string text;
    };
    const float inf = std::numeric_limits<float>::infinity();
    for (const Case& c : std::vector<Case>{{ScalarType::UInt8, 256, "256"},
                                           {ScalarType::UInt8, -1, "-1"},
                                           {ScalarType::UInt8, 0.5f, "0.5"},
                                           {ScalarType::Int16, 32768, "32768"},
                                           {ScalarType::Int16, -32769, "-32769"},
                                           {ScalarType::Int16, -2.5f, "-2.5"},
                                           {ScalarType::UInt16, 65536, "65536"},
                                           {ScalarType::UInt16, -1, "-1"},
                                           {ScalarType::UInt16, 100.25f, "100.25"},
                                           {ScalarType::UInt16, inf, "inf"},
                                           {ScalarType::Float32, std::numeric_limits<float>::quiet_NaN(), "nan"},
                                           {ScalarType::Float32, -inf, "-inf"}}) {
        SCOPED_TRACE(std::string(scalarTypeName(c.type)) + " " + c.text);
        PreparedVolume p = samplePrepared({13, 7, 5}, c.type);
        p.scalars.values[40] = c.value;
        p.scalars.values[41] = c.value;  // the first one is named
        expectWriteRefused(bad, p,
                           "cannot write: scalar " + c.text + " at voxel 40 is not a " +
                               std::string(scalarTypeName(c.type)) + " value");
    }
}

TEST_F(IoPreparedFile, RefusesToWriteArraysOrNumbersThatDoNotFit) {
    auto refused = [&](const std::function<void(PreparedVolume&)>& edit, const std::string& problem) {
        PreparedVolume p = prepared;
        edit(p);
        expectWriteRefused(bad, p, "cannot write: " + problem);
    };
    refused([](PreparedVolume& p) { p.scalars.values.pop_back(); }, "the scalars must hold one value per voxel");
    refused([](PreparedVolume& p) { p.regions.label.push_back(0); }, "the labels must hold one value per voxel");
    refused([](PreparedVolume& p) { p.regions.dims.z = 6; }, "region labels and scalars have different dims");
    refused([](PreparedVolume& p) { p.fields.pc.pop_back(); }, "chunk 'pc' does not hold one value per voxel");
    refused([](PreparedVolume& p) { p.classification.table.sigma.pop_back(); },
            "the transfer table's sigma and colour differ in size");
    refused(
        [](PreparedVolume& p) {
            p.classification.table.sigma.clear();
            p.classification.table.colour.clear();
        },
        "the transfer table holds 0 entries (must be 1 to 1048576)");
    refused(
        [](PreparedVolume& p) {
            p.classification.table.sigma.assign(kMaxTransferTableEntries + 1, 0.0f);
            p.classification.table.colour.assign(kMaxTransferTableEntries + 1, {0, 0, 0});
        },
        "the transfer table holds 1048577 entries (must be 1 to 1048576)");
    refused([](PreparedVolume& p) { p.classification.table.step = 0; },
            "'transferTable.step' must be a finite number > 0");
    refused([](PreparedVolume& p) { p.classification.table.lo = std::numeric_limits<double>::infinity(); },
            "'transferTable.lo' must be a finite number");
    refused([](PreparedVolume& p) { p.classification.flatGradient = -1; },
            "'flatGradient' must be a finite number >= 0");
    refused([](PreparedVolume& p) { p.classification.referenceStep = 0; },
            "'referenceStep' must be a finite number > 0");
    refused([](PreparedVolume& p) { p.classification.table.sigma[3] = -0.25f; },
            "transfer table entry 3 has sigma -0.25 (must be finite and >= 0)");
    refused([](PreparedVolume& p) { p.classification.table.colour[4][2] = std::numeric_limits<float>::infinity(); },
            "transfer table entry 4 has a colour that is not finite");

    // Compression options out of range.
    for (std::size_t block : {std::size_t(0), kMaxPreparedBlockBytes + 1}) {
        SCOPED_TRACE(block);
        expectWriteRefused(bad, prepared, "cannot write: blocks of " + std::to_string(block) +
                                              " bytes (must be 1 to 1073741824)", {kPreparedZstdLevel, block});
    }
    for (int level : {ZSTD_minCLevel() - 1, ZSTD_maxCLevel() + 1}) {
        SCOPED_TRACE(level);
        expectWriteRefused(bad, prepared,
                           "cannot write: zstd level " + std::to_string(level) + " (must be " +
                               std::to_string(ZSTD_minCLevel()) + " to " + std::to_string(ZSTD_maxCLevel()) + ")",
                           {level, kPreparedBlockBytes});
    }
}

TEST_F(IoPreparedFile, WritingIsAtomic) {
    // A folder that does not exist: nothing written, a clear error.
    fs::path missing = dir / "no-such-folder" / "out.vprep";
    try {
        writePrepared(missing, prepared);
        ADD_FAILURE() << "write into a missing folder succeeded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(missing));

    // An inconsistent volume is refused and the existing file is left as it was, with no temporary beside it.
    std::vector<char> before = readBytes(good);
    PreparedVolume broken = prepared;
    broken.scalars.values.pop_back();
    EXPECT_THROW(writePrepared(good, broken), InputError);
    broken = prepared;
    broken.scalars.values[0] = 0.5f;  // not an int16
    EXPECT_THROW(writePrepared(good, broken), InputError);
    EXPECT_EQ(readBytes(good), before);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(IoPreparedFile, RefusesPartialOctants) {
    PreparedVolume p = prepared;
    p.fields.acd[5].clear();
    EXPECT_THROW(writePrepared(bad, p), InputError);
    EXPECT_FALSE(fs::exists(bad));
}

}  // namespace
}  // namespace vr

namespace vr {
namespace {

// A label map of `type` beside the sample volume: labels from the noise (up to 700 in 16 bits), classes whose
// numbers do not round trip through a short decimal.
LabelMap sampleLabels(const PreparedVolume& p, ScalarType type) {
    LabelMap m;
    const int count = type == ScalarType::UInt8 ? 200 : 701;
    for (std::size_t i = 0; i < p.scalars.values.size(); ++i)
        m.label.push_back(uint16_t((i * 37) % std::size_t(count)));
    m.type = type;
    for (int l = 0; l < count; ++l) {
        m.classes.sigma.push_back(l == 0 ? 0.0f : float(l) / 7.0f);
        m.classes.colour.push_back({float(l) / 701, 1 - float(l) / 701, 1.0f / 3});
    }
    m.source = "labels.nii.gz";
    m.colourTable = "colours.txt";
    return m;
}

TEST(IoPreparedFileLabels, RoundTripInEitherType) {
    const fs::path dir = test::scratchDir("io_prepared_file_labels");
    for (ScalarType type : {ScalarType::UInt8, ScalarType::UInt16}) {
        PreparedVolume p = samplePrepared({13, 7, 5});
        p.labels = sampleLabels(p, type);
        const fs::path path = dir / "labelled.vprep";
        writePrepared(path, p, {kPreparedZstdLevel, kSmallBlock});
        const PreparedVolume r = readPrepared(path);
        ASSERT_TRUE(r.labels);
        EXPECT_EQ(r.labels->label, p.labels->label);
        EXPECT_EQ(r.labels->type, type);
        EXPECT_EQ(r.labels->classes, p.labels->classes);
        EXPECT_EQ(r.labels->source, "labels.nii.gz");
        EXPECT_EQ(r.labels->colourTable, "colours.txt");
        EXPECT_EQ(r.scalars.values, p.scalars.values);
        // A file without a label map reads back without one.
        p.labels.reset();
        writePrepared(path, p);
        EXPECT_FALSE(readPrepared(path).labels);
    }
}

TEST(IoPreparedFileLabels, RefusesInconsistentLabelMaps) {
    const fs::path dir = test::scratchDir("io_prepared_file_labels_bad");
    PreparedVolume p = samplePrepared({13, 7, 5});
    p.labels = sampleLabels(p, ScalarType::UInt16);
    p.labels->type = ScalarType::UInt8;  // labels up to 700
    expectWriteRefused(dir / "a.vprep", p, "the label map's uint8 type does not hold its labels");
    p.labels = sampleLabels(p, ScalarType::UInt8);
    p.labels->label.pop_back();
    expectWriteRefused(dir / "b.vprep", p, "the label map must hold one label per voxel");
    p.labels = sampleLabels(p, ScalarType::UInt8);
    p.labels->classes.sigma[3] = -1;
    expectWriteRefused(dir / "c.vprep", p, "label 3's class has a sigma");

    // A header that lost its labelMap, or whose labelMap says another number of labels, is refused.
    p.labels = sampleLabels(p, ScalarType::UInt8);
    const fs::path good = dir / "good.vprep", bad = dir / "bad.vprep";
    writePrepared(good, p);
    Parts parts = split(good);
    parts.header.erase("labelMap");
    join(bad, parts);
    expectRejected(bad, "bad header: chunk 'labelMap' without a 'labelMap'");
    parts = split(good);
    parts.header["labelMap"]["entries"] = 199;
    join(bad, parts);
    expectRejected(bad, "chunk 'labelTable' holds 3200 bytes but a label table of 199 entries needs 3184");
    parts = split(good);
    parts.header["labelMap"]["type"] = "int16";
    join(bad, parts);
    expectRejected(bad, "bad header: 'labelMap.type': 'int16' (expected uint8 or uint16)");
}

}  // namespace
}  // namespace vr
