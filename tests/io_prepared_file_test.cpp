// The prepared file: exact round trip, selective reading, and a clear InputError for every kind of damage.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <functional>

#include "core/errors.h"
#include "core/extent_code.h"
#include "io/prepared_file.h"
#include "datasets/phantoms.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

// A prepared volume with every chunk present and distinct, reproducible contents (not a real segmentation:
// the format must carry any bytes).
PreparedVolume samplePrepared(Vec3i dims) {
    Volume noise = noisePhantom(dims, 7, 0, 255, {0.5, 0.75, 2.0});
    PreparedVolume p;
    p.classified.grid = noise.grid;
    p.classified.grid.origin = {-1.5, 2.25, 3};
    p.classified.referenceStep = 0.5;
    std::size_t n = noise.grid.voxels();
    for (std::size_t i = 0; i < n; ++i) {
        float f = noise.values[i];
        p.classified.sigma.push_back(f * 0.01f);
        p.classified.colour.push_back({f / 255, 1 - f / 255, 0.25f});
        p.classified.normal.push_back({0.6f, -0.8f, f > 128 ? 0.0f : 1e-7f});
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
    for (const json& c : header["chunks"])
        if (c["name"] == name) return c;
    ADD_FAILURE() << "no chunk " << name;
    return {};
}

// readPrepared must throw an InputError naming the file and containing `problem`.
void expectRejected(const fs::path& p, const std::string& problem, unsigned fields = kFieldPC | kFieldACD | kFieldEACD) {
    try {
        readPrepared(p, fields, true);
        ADD_FAILURE() << "read of " << p << " succeeded; expected: " << problem;
    } catch (const InputError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(p.string()), std::string::npos) << m;
        EXPECT_NE(m.find(problem), std::string::npos) << "message: " << m << "\nexpected: " << problem;
    }
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
    EXPECT_EQ(r.classified.grid, p.classified.grid);
    EXPECT_EQ(r.classified.referenceStep, p.classified.referenceStep);
    EXPECT_EQ(r.classified.sigma, p.classified.sigma);
    EXPECT_EQ(r.classified.colour, p.classified.colour);
    EXPECT_EQ(r.classified.normal, p.classified.normal);
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
    EXPECT_FALSE(readPrepared(bad, 0, false).meta.rayProbe);
}

// An older volprep's probe (per-octant counts, no views) is no probe, and a caster's malformed counts no counts:
// the file still reads, and --caster auto chooses among what is left.
TEST_F(IoPreparedFile, ReadsAnOlderRayProbeAsNone) {
    Parts parts = split(good);
    json& probe = parts.header["metadata"]["statistics"]["rayProbe"];
    probe["casters"]["acd"]["singleSamples"] = std::vector<double>(kOctants, 1.0);
    join(bad, parts);
    std::optional<RayProbe> read = readPrepared(bad, 0, false).meta.rayProbe;
    ASSERT_TRUE(read);
    EXPECT_EQ(read->primitive, prepared.meta.rayProbe->primitive);
    EXPECT_FALSE(read->acd);

    for (const char* key : {"leaps", "singleSamples"})
        probe["casters"]["primitive"][key] = std::vector<double>(kOctants, 1.0);
    probe.erase("views");
    probe["raysPerSide"] = 32;
    join(bad, parts);
    const PreparedVolume older = readPrepared(bad, 0, false);
    EXPECT_FALSE(older.meta.rayProbe);
    EXPECT_FALSE(older.meta.statistics.contains("rayProbe"));
}

TEST_F(IoPreparedFile, ReadsTheHeaderAlone) {
    const PreparedHeader h = readPreparedHeader(good);
    EXPECT_EQ(h.grid, prepared.classified.grid);
    EXPECT_EQ(h.meta.source, prepared.meta.source);
    EXPECT_EQ(h.meta.segmentation, prepared.meta.segmentation);
    EXPECT_EQ(h.meta.statistics, prepared.meta.statistics);
    EXPECT_EQ(h.meta.rayProbe, prepared.meta.rayProbe);
    const std::size_t n = prepared.classified.grid.voxels();
    EXPECT_EQ(h.fieldBytes.pc, n);
    EXPECT_EQ(h.fieldBytes.acd, kOctants * n);
    EXPECT_EQ(h.fieldBytes.eacd, kOctants * 3 * n);  // exact extents

    // A damaged chunk is not read; a damaged header is.
    std::vector<char> b = readBytes(good);
    b[dataStart(good)] ^= 0x5a;
    writeBytes(bad, b);
    EXPECT_EQ(readPreparedHeader(bad).grid, prepared.classified.grid);
    Parts parts = split(good);
    parts.header["grid"]["dims"] = {13, 7, 6};
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
    PreparedVolume pc = readPrepared(good, kFieldPC, false);
    EXPECT_EQ(pc.fields.pc, prepared.fields.pc);
    EXPECT_FALSE(pc.fields.hasACD());
    EXPECT_FALSE(pc.fields.hasEACD());
    EXPECT_FALSE(pc.classified.hasNormals());
    EXPECT_EQ(pc.classified.sigma, prepared.classified.sigma);

    PreparedVolume eacd = readPrepared(good, kFieldEACD, true);
    EXPECT_FALSE(eacd.fields.hasPC());
    EXPECT_FALSE(eacd.fields.hasACD());
    EXPECT_EQ(eacd.fields.eacd, prepared.fields.eacd);
    EXPECT_EQ(eacd.classified.normal, prepared.classified.normal);

    PreparedVolume none = readPrepared(good, 0, false);
    EXPECT_FALSE(none.fields.hasPC() || none.fields.hasACD() || none.fields.hasEACD());
    EXPECT_EQ(none.regions.label, prepared.regions.label);
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
    p.classified.normal.clear();
    p.fields = {};
    p.fields.dims = p.classified.grid.dims;
    p.fields.pc = prepared.fields.pc;
    writePrepared(bad, p);
    PreparedVolume r = readPrepared(bad, kFieldPC, true);
    EXPECT_FALSE(r.classified.hasNormals());  // normals are optional (volprep --no-normals)
    EXPECT_EQ(r.fields.pc, p.fields.pc);
    expectRejected(bad, "has no ACD distance field", kFieldACD);
    expectRejected(bad, "has no EACD distance field", kFieldEACD);

    p.fields.pc.clear();
    writePrepared(bad, p);
    expectRejected(bad, "has no PC distance field", kFieldPC);
}

TEST_F(IoPreparedFile, RejectsAMissingFile) { expectRejected(dir / "absent.vprep", "no such file"); }

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
    const std::size_t voxels = prepared.classified.grid.voxels();
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

TEST_F(IoPreparedFile, RejectsTheVersionBeforeCodedExtents) {
    // Version 1 stored EACD as 3 bytes per octant with no eacdCode: refused with the way out, not misread.
    std::vector<char> b = readBytes(good);
    const uint32_t v = 1;
    std::memcpy(b.data() + 8, &v, 4);
    writeBytes(bad, b);
    expectRejected(bad, "prepared format version 1, this build reads version 2 (run volprep again)");
}

TEST_F(IoPreparedFile, RejectsAnotherVersion) {
    std::vector<char> b = readBytes(good);
    uint32_t v = kPreparedFormatVersion + 1;
    std::memcpy(b.data() + 8, &v, 4);
    writeBytes(bad, b);
    expectRejected(bad, "prepared format version " + std::to_string(v) + ", this build reads version " +
                            std::to_string(kPreparedFormatVersion));
}

TEST_F(IoPreparedFile, RejectsATruncatedFileAtEveryPart) {
    std::vector<char> b = readBytes(good);
    uint64_t data = dataStart(good);
    json header = split(good).header;
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
                                           {data, "truncated: chunk 'sigma'"},
                                           {labels + 3, "truncated: chunk 'labels'"},
                                           {b.size() - 1, "truncated: chunk 'eacd7'"}}) {
        SCOPED_TRACE(cut.size);
        writeBytes(bad, std::vector<char>(b.begin(), b.begin() + std::ptrdiff_t(cut.size)));
        expectRejected(bad, cut.problem);
    }
}

TEST_F(IoPreparedFile, RejectsAFlippedByteInAChunk) {
    json header = split(good).header;
    for (const char* name : {"sigma", "colour", "normal", "labels", "pc", "acd0", "eacd7"}) {
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
                               "chunk 'sigma' holds 1820 bytes but grid 13x7x6 needs 2184");
}

TEST_F(IoPreparedFile, RejectsAbsurdDims) {
    for (json dims : {json{100000, 100000, 100000}, json{60000, 60000, 60000}, json{0, 7, 5}, json{13, -7, 5}}) {
        SCOPED_TRACE(dims.dump());
        expectEditedHeaderRejected([&](json& h) { h["grid"]["dims"] = dims; }, "absurd grid dims");
    }
}

TEST_F(IoPreparedFile, RejectsABadChunkTable) {
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["type"] = "float64"; },
                               "chunk 'sigma' should be 1 x float32");
    expectEditedHeaderRejected([](json& h) { h["chunks"][1]["name"] = "sigma"; }, "chunk 'sigma' appears twice");
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["name"] = "opacity"; }, "unknown chunk 'opacity'");
    expectEditedHeaderRejected([](json& h) { h.erase("grid"); }, "bad header: missing or invalid 'grid'");
    expectEditedHeaderRejected([](json& h) { h["chunks"][0]["offset"] = uint64_t(1) << 40; },
                               "truncated: chunk 'sigma'");
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
    broken.classified.sigma.pop_back();
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
