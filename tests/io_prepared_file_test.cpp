// The prepared file: exact round trip, selective reading, and a clear InputError for every kind of damage.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

#include "core/errors.h"
#include "core/extent_code.h"
#include "io/prepared_file.h"
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

// Overwrites `bytes` bytes of chunk `name` from `at` (bytes into the chunk) and updates the chunk's CRC-32, so that
// the chunk is well formed but holds what the writer would refuse.
void patchChunk(Parts& parts, const std::string& name, uint64_t at, const void* bytes, std::size_t size) {
    json& c = chunkEntryToEdit(parts.header, name);
    const uint64_t offset = c["offset"].get<uint64_t>();
    std::memcpy(parts.data.data() + offset + at, bytes, size);
    c["crc32"] = uint32_t(crc32_z(0, reinterpret_cast<const Bytef*>(parts.data.data() + offset),
                                  c["bytes"].get<uint64_t>()));
}

// readPrepared must throw an InputError naming the file and containing `problem`.
void expectRejected(const fs::path& p, const std::string& problem, unsigned fields = kFieldPC | kFieldACD | kFieldEACD) {
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
void expectWriteRefused(const fs::path& p, const PreparedVolume& prepared, const std::string& problem) {
    try {
        writePrepared(p, prepared);
        ADD_FAILURE() << "write of " << p << " succeeded; expected: " << problem;
    } catch (const InputError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(p.string()), std::string::npos) << m;
        EXPECT_NE(m.find(problem), std::string::npos) << "message: " << m << "\nexpected: " << problem;
    }
    EXPECT_FALSE(fs::exists(p));
}

class IoPreparedFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir = test::scratchDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
        good = dir / "good.vprep";
        prepared = samplePrepared({13, 7, 5});
        writePrepared(good, prepared);
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

// The scalars are stored in the volume's own type, each exactly, the ends of the type's range included; the file is
// the scalar bytes, 4 label bytes and the field bytes per voxel, and the table.
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
        EXPECT_EQ(parts.data.size(), n * (scalarBytes(type) + 4 + 1 + kOctants * (1 + 3)) + 37 * 16);
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
    std::memcpy(entry5, parts.data.data() + c["offset"].get<std::size_t>() + 5 * 16, sizeof(entry5));
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
    const std::size_t exactBytes = split(good).data.size();
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
        EXPECT_EQ(split(bad).data.size(), exactBytes - kOctants * voxels * (3 - extentCodeBytes(code)));

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
    // normal) instead of the scalars and the table: refused with the way out, not misread.
    for (uint32_t v : {1u, 2u}) {
        std::vector<char> b = readBytes(good);
        std::memcpy(b.data() + 8, &v, 4);
        writeBytes(bad, b);
        expectRejected(bad, "prepared format version " + std::to_string(v) +
                                ", this build reads version 3 (run volprep again)");
    }
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
    for (const Cut& cut : std::vector<Cut>{{0, "not a prepared file (only 0 bytes"},
                                           {7, "not a prepared file (only 7 bytes"},
                                           {19, "not a prepared file (only 19 bytes"},
                                           {20, "truncated header"},
                                           {20 + 10, "truncated header"},
                                           {data - 2, "truncated header"},
                                           {data, "truncated: chunk 'scalars'"},
                                           {table + 5, "truncated: chunk 'table'"},
                                           {labels + 3, "truncated: chunk 'labels'"},
                                           {b.size() - 1, "truncated: chunk 'eacd7'"}}) {
        SCOPED_TRACE(cut.size);
        writeBytes(bad, std::vector<char>(b.begin(), b.begin() + std::ptrdiff_t(cut.size)));
        expectRejected(bad, cut.problem);
    }
}

TEST_F(IoPreparedFile, RejectsAFlippedByteInAChunk) {
    json header = split(good).header;
    for (const char* name : {"scalars", "table", "labels", "pc", "acd0", "eacd7"}) {
        SCOPED_TRACE(name);
        std::vector<char> b = readBytes(good);
        json c = chunkEntry(header, name);
        b[dataStart(good) + c["offset"].get<uint64_t>() + c["bytes"].get<uint64_t>() / 2] ^= 0x01;
        writeBytes(bad, b);
        expectRejected(bad, std::string("chunk '") + name + "' checksum mismatch");
    }
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
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["type"] = "uint8"; }, "chunk 'table' should be 4 x float32");
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["components"] = 3; },
                               "chunk 'table' should be 4 x float32");
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["name"] = "scalars"; }, "chunk 'scalars' appears twice");
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["name"] = "opacity"; }, "unknown chunk 'opacity'");
    // The classified volume of version 2 is no chunk of version 3.
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
                                           {"transferTable.entries", nullptr, "bad header: missing or invalid 'entries'"}}) {
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
             {"offset", -5}, {"offset", 1e30}, {"bytes", 12.5}, {"crc32", uint64_t(1) << 40}, {"components", "3"}}) {
        const std::string& key = entry.first;  // a named reference: clang 14 cannot capture structured bindings
        const json& value = entry.second;
        SCOPED_TRACE(key + " = " + value.dump());
        expectEditedHeaderRejected([&](json& h) { h["chunks"][2][key] = value; },
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
    refused([](PreparedVolume& p) { p.classification.flatGradient = -1; }, "'flatGradient' must be a finite number >= 0");
    refused([](PreparedVolume& p) { p.classification.referenceStep = 0; },
            "'referenceStep' must be a finite number > 0");
    refused([](PreparedVolume& p) { p.classification.table.sigma[3] = -0.25f; },
            "transfer table entry 3 has sigma -0.25 (must be finite and >= 0)");
    refused([](PreparedVolume& p) { p.classification.table.colour[4][2] = std::numeric_limits<float>::infinity(); },
            "transfer table entry 4 has a colour that is not finite");
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
