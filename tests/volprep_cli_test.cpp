// volprep end to end: the built executable prepares real and synthetic volumes that read back consistently,
// and every bad input exits non-zero with "volprep: <message>" on stderr and leaves no output behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "io/prepared_file.h"
#include "datasets/phantoms.h"
#include "support/cli.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

using test::slurp;
using Outcome = test::CliOutcome;
constexpr auto volprep = [](const std::string& args) { return test::runVolprep(args); };
constexpr auto q = test::shellQuote;

test::DatasetEntry headsq() { return test::rawDataset("vtk_headsq_ct_64x64x93_uint16"); }

std::string spacingFlag(const Vec3d& s) {
    std::ostringstream o;
    o.precision(17);
    o << "--spacing " << s.x << "," << s.y << "," << s.z;
    return o.str();
}

// The head CT with its transfer function and manifest spacing, written to `output`.
std::string headsqArgs(const fs::path& output) {
    test::DatasetEntry e = headsq();
    return q(test::datasetsDir() / e.file) + " --tf " + q(test::datasetsDir() / e.tf) + " " + spacingFlag(e.spacing) +
           " -o " + q(output);
}

// Mean of get(v[i]) over a field (a vector or an ExtentField).
template <typename Field, typename Get>
double mean(const Field& v, Get get) {
    double s = 0;
    for (std::size_t i = 0; i < v.size(); ++i) s += get(v[i]);
    return s / double(v.size());
}

TEST(VolprepCli, PreparesTheHeadCtAndItReadsBackConsistently) {
    fs::path dir = test::scratchDir("volprep_headsq");
    fs::path out = dir / "headsq.vprep";
    Outcome r = volprep(headsqArgs(out));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;  // no progress bars when stderr is not a terminal
    for (const char* word : {"voxels", "regions", "mean PC radius", "mean ACD edge", "mean EACD extents", "load",
                             "classify", "segment", "eacd", "write"})
        EXPECT_NE(r.out.find(word), std::string::npos) << word << " missing from\n" << r.out;

    PreparedVolume p = readPrepared(out);
    test::DatasetEntry e = headsq();
    EXPECT_EQ(p.grid().dims, e.dims);
    EXPECT_EQ(p.grid().spacing, e.spacing);
    EXPECT_EQ(p.meta.classification, slurp(test::datasetsDir() / e.tf));
    EXPECT_EQ(p.meta.source, (test::datasetsDir() / e.file).string());
    EXPECT_EQ(p.meta.segmentation.opacityThreshold, 0.01);
    EXPECT_EQ(p.meta.segmentation.angleThresholdDeg, 3.0);
    EXPECT_TRUE(p.meta.segmentation.useNormals);
    EXPECT_TRUE(p.meta.segmentation.trilinear);  // regions for the default sampling
    EXPECT_EQ(p.scalars.sourceType, ScalarType::UInt16);
    ASSERT_TRUE(p.fields.hasPC() && p.fields.hasACD() && p.fields.hasEACD());

    // The statistics stored in the file describe the arrays in it.
    const nlohmann::json& s = p.meta.statistics;
    std::size_t n = p.grid().voxels();
    EXPECT_EQ(s["voxels"].get<std::size_t>(), n);
    EXPECT_EQ(s["regions"].get<uint32_t>(), p.regions.count);
    EXPECT_EQ(*std::max_element(p.regions.label.begin(), p.regions.label.end()) + 1, p.regions.count);
    EXPECT_DOUBLE_EQ(s["meanRegionSize"].get<double>(), double(n) / p.regions.count);
    EXPECT_NEAR(s["leaps"]["pcMeanRadius"].get<double>(), mean(p.fields.pc, [](uint8_t r) { return r; }), 1e-9);
    for (int o = 0; o < kOctants; ++o) {
        double acd = mean(p.fields.acd[o], [](uint8_t k) { return k; });
        EXPECT_NEAR(s["leaps"]["acdMeanEdge"][o].get<double>(), acd, 1e-9);
        // Every homogeneous cube has one corner per octant, so the mean ACD edge is the same in all octants.
        EXPECT_NEAR(acd, s["leaps"]["acdMeanEdge"][0].get<double>(), 1e-9) << "octant " << o;
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(s["leaps"]["eacdMeanExtent"][o][a].get<double>(),
                        mean(p.fields.eacd[o], [a](const Extents& x) { return x[a]; }), 1e-9);
    }
    EXPECT_EQ(p.fields.eacdCode(), ExtentCode::Log16);  // the default: 2 bytes per octant
    EXPECT_EQ(s["eacdCode"], "log16");
    EXPECT_EQ(s["bytes"]["eacd"].get<std::size_t>(), 16 * n);
    EXPECT_EQ(s["bytes"]["scalars"].get<std::size_t>(), 2 * n);  // uint16, as the source
    EXPECT_EQ(s["bytes"]["table"].get<std::size_t>(), 16 * p.classification.table.size());
    for (const char* stage : {"load", "classify", "segment", "pc", "acd", "eacd"})
        EXPECT_GE(s["seconds"][stage].get<double>(), 0.0) << stage;
    // The ray probe behind --caster auto, with counts for every field built.
    ASSERT_TRUE(p.meta.rayProbe);
    EXPECT_TRUE(p.meta.rayProbe->pc && p.meta.rayProbe->acd && p.meta.rayProbe->eacd);
}

TEST(VolprepCli, StoresEacdInTheCodeAsked) {
    fs::path dir = test::scratchDir("volprep_eacd_code");
    std::map<ExtentCode, PreparedVolume> p;
    for (ExtentCode code : {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8}) {
        const std::string name(extentCodeName(code));
        fs::path out = dir / (name + ".vprep");
        Outcome r = volprep(headsqArgs(out) + " --fields eacd --no-normals --eacd-code " + name);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find(name + " code"), std::string::npos) << r.out;
        p[code] = readPrepared(out, kFieldEACD);
        EXPECT_EQ(p[code].fields.eacdCode(), code);
        EXPECT_EQ(p[code].meta.statistics["bytes"]["eacd"].get<std::size_t>(),
                  kOctants * extentCodeBytes(code) * p[code].grid().voxels());
    }
    // The coded files hold the exact boxes rounded down by their code.
    for (ExtentCode code : {ExtentCode::Log16, ExtentCode::Joint8}) {
        DistanceFields rounded = p[ExtentCode::Exact].fields;
        quantiseEACD(rounded, code);
        EXPECT_EQ(rounded.eacd, p[code].fields.eacd) << extentCodeName(code);
    }
}

TEST(VolprepCli, BuildsOnlyTheRequestedFieldsAndRegions) {
    fs::path dir = test::scratchDir("volprep_fields");
    fs::path out = dir / "pc.vprep";
    Outcome r = volprep(headsqArgs(out) + " --fields pc --no-normals --to 0.05 --ta 0 --nearest");
    ASSERT_EQ(r.status, 0) << r.err;
    PreparedVolume p = readPrepared(out, kFieldPC);
    EXPECT_TRUE(p.fields.hasPC());
    EXPECT_FALSE(p.meta.segmentation.useNormals);
    EXPECT_FALSE(p.meta.segmentation.trilinear);
    EXPECT_EQ(p.meta.segmentation.opacityThreshold, 0.05);
    EXPECT_FALSE(p.meta.statistics["leaps"].contains("acdMeanEdge"));
    EXPECT_THROW(readPrepared(out, kFieldACD), InputError);
    EXPECT_THROW(readPrepared(out, kFieldEACD), InputError);
}

// A raw file whose name says nothing: dims, type, spacing and byte order come from the flags.
TEST(VolprepCli, ReadsHeaderlessRawWithFlagsInEitherByteOrder) {
    fs::path dir = test::scratchDir("volprep_raw");
    Volume shells = shellsPhantom({24, 20, 16});
    for (bool big : {false, true}) {
        std::vector<int16_t> v(shells.values.begin(), shells.values.end());
        if (big)
            for (int16_t& x : v) x = int16_t(uint16_t(x) << 8 | uint16_t(x) >> 8);
        std::ofstream(dir / (big ? "be.bin.raw" : "le.bin.raw"), std::ios::binary)
            .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * 2));
    }
    std::string common = " --dims 24x20x16 --type int16 --spacing 1,1,2 --tf " +
                         q(test::datasetsDir() / "cranium_ct.tf.json");
    ASSERT_EQ(volprep(q(dir / "le.bin.raw") + common + " -o " + q(dir / "le.vprep")).status, 0);
    Outcome r = volprep(q(dir / "be.bin.raw") + common + " --big-endian -o " + q(dir / "be.vprep"));
    ASSERT_EQ(r.status, 0) << r.err;
    PreparedVolume le = readPrepared(dir / "le.vprep"), be = readPrepared(dir / "be.vprep");
    EXPECT_EQ(le.grid().dims, Vec3i(24, 20, 16));
    EXPECT_EQ(le.grid().spacing, Vec3d(1, 1, 2));
    EXPECT_EQ(le.scalars.sourceType, ScalarType::Int16);
    EXPECT_EQ(le.scalars.values, shells.values);
    EXPECT_EQ(le.scalars.values, be.scalars.values);
    EXPECT_EQ(le.classification, be.classification);
    EXPECT_EQ(le.regions.label, be.regions.label);
    EXPECT_EQ(le.fields.eacd, be.fields.eacd);
    // The bone shell is opaque somewhere, air is not.
    const std::vector<float>& sigma = le.classification.table.sigma;
    EXPECT_GT(*std::max_element(sigma.begin(), sigma.end()), 0.0f);
    EXPECT_EQ(sigma[0], 0.0f);
}

// volphantom writes NAME_DxDxD_TYPE.raw, which volprep reads with no raw flags.
TEST(VolprepCli, PreparesAPhantomWrittenByVolphantom) {
    fs::path dir = test::scratchDir("volprep_phantom");
    fs::path volphantom = test::volphantomExecutable();
    std::string cmd = volphantom.string() + " engine --dims 32x24x16 -o " + q(dir) + " >/dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    fs::path raw = dir / "engine_32x24x16_uint8.raw";
    std::string bytes = slurp(raw);
    Volume engine = enginePhantom({32, 24, 16});
    ASSERT_EQ(bytes.size(), engine.values.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) ASSERT_EQ(uint8_t(bytes[i]), engine.values[i]) << i;

    Outcome r = volprep(q(raw) + " --tf " + q(test::datasetsDir() / "sim.tf.json") + " --nearest --to 0 --ta 0 -o " +
                        q(dir / "engine.vprep"));
    ASSERT_EQ(r.status, 0) << r.err;
    PreparedVolume p = readPrepared(dir / "engine.vprep");
    EXPECT_EQ(p.grid().dims, Vec3i(32, 24, 16));
    // Blocky: a few hundred regions for 12288 voxels, and the air around the part is one region.
    EXPECT_LT(p.regions.count, 1000u);
    EXPECT_EQ(p.regions.label[0], p.regions.label[voxelCount(p.regions.dims) - 1]);
}

// volphantom checks its dims before it allocates: dims that are not positive, or that need more memory than the
// machine has, are refused naming --dims, and nothing is written.
TEST(VolprepCli, VolphantomRefusesAbsurdDims) {
    const fs::path dir = test::scratchDir("volprep_phantom_dims");
    for (const char* dims : {"0x4x4", "4x-4x4", "100000x100000x100000"}) {
        const test::CliOutcome r =
            test::runCli(test::volphantomExecutable(), std::string("noise --dims ") + dims + " -o " + q(dir));
        EXPECT_EQ(r.status, 1) << dims;
        EXPECT_EQ(r.err.rfind("volphantom: --dims: ", 0), 0u) << r.err;
    }
    EXPECT_TRUE(fs::is_empty(dir));
}

// On a terminal each stage draws a progress bar; --quiet leaves the terminal to errors.
TEST(VolprepCli, ProgressBarsOnATerminalAndNoneWithQuiet) {
    const fs::path dir = test::scratchDir("volprep_quiet");
    const fs::path volprep = test::volprepExecutable();
    const test::CliOutcome shown = test::runOnTerminal(volprep, headsqArgs(dir / "a.vprep"));
    ASSERT_EQ(shown.status, 0) << shown.out;
    for (const char* stage : {"load ", "classify ", "segment ", "fields ", "write "})
        EXPECT_NE(shown.out.find(std::string(stage)), std::string::npos) << stage << " in\n" << shown.out;
    EXPECT_NE(shown.out.find("100%"), std::string::npos) << shown.out;
    const test::CliOutcome quiet = test::runOnTerminal(volprep, headsqArgs(dir / "b.vprep") + " --quiet");
    ASSERT_EQ(quiet.status, 0) << quiet.out;
    EXPECT_EQ(quiet.out, "");
    EXPECT_TRUE(fs::exists(dir / "b.vprep"));
}

TEST(VolprepCli, HelpDescribesEveryFlag) {
    fs::path dir = test::scratchDir("volprep_help");
    Outcome r = volprep("--help");
    EXPECT_EQ(r.status, 0);
    for (const char* flag : {"--output", "--tf", "--window", "--level", "--list-presets", "--to", "--ta", "--fields",
                             "--trilinear", "--nearest", "--no-normals", "--eacd-code", "--dims", "--type", "--spacing",
                             "--big-endian"})
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

// --list-presets needs no volume; --tf takes a preset's name, --window and --level a ramp (coloured by --tf when
// given), and the prepared file keeps the transfer function it was classified with.
TEST(VolprepCli, PresetsByNameAndWindowLevel) {
    const Outcome list = volprep("--list-presets");
    ASSERT_EQ(list.status, 0) << list.err;
    EXPECT_EQ(list.err, "");
    for (const char* line : {"CT-Bone         -3024 .. 3071 HU, visible above 150: bone", "CT-AAA ", "CT-Cardiac ",
                             "CT-Lung ", "CT-Muscle ", "CT-Soft-Tissue ", "MR-Default ", "MR-Angio ", "MR-T2-Brain "})
        EXPECT_NE(list.out.find(line), std::string::npos) << line << " missing from\n" << list.out;

    const fs::path dir = test::scratchDir("volprep_presets");
    const test::DatasetEntry e = headsq();
    const std::string in = q(test::datasetsDir() / e.file) + " " + spacingFlag(e.spacing) + " --fields pc -o ";
    struct Case {
        std::string flags, name;
    };
    for (const Case& c : std::vector<Case>{{" --tf mr-default", "MR-Default"},
                                           {" --window 2000 --level 1000", "window 2000 level 1000"},
                                           {" --tf CT-Bone --window 1000 --level 1500",
                                            "CT-Bone, window 1000 level 1500"},
                                           {" --window 100 --level 0 --tf " + q(test::datasetsDir() / e.tf),
                                            "ct-headsq, window 100 level 0"}}) {
        const Outcome r = volprep(in + q(dir / "p.vprep") + c.flags);
        ASSERT_EQ(r.status, 0) << c.flags << ": " << r.err;
        const std::string kept = readPreparedHeader(dir / "p.vprep").meta.classification;
        EXPECT_NE(kept.find("\"Name\": \"" + c.name + "\""), std::string::npos) << kept;
    }
}

// Each bad run: non-zero exit, "volprep: " and the problem on stderr, and no file at the output path.
TEST(VolprepCli, BadInputFailsClearlyAndWritesNothing) {
    fs::path dir = test::scratchDir("volprep_bad");
    test::DatasetEntry e = headsq();
    std::string in = q(test::datasetsDir() / e.file), tf = " --tf " + q(test::datasetsDir() / e.tf);
    fs::path out = dir / "out.vprep";
    fs::path garbage = dir / "garbage_8x8x8_uint8.raw";
    std::ofstream(garbage) << "too short";
    struct Case {
        std::string args, message;
    };
    for (const Case& c : std::vector<Case>{
             {in + " -o " + q(out), "At least 1 option from [--tf,--window,--level] is required"},
             {in + tf + " --to -1e-9 -o " + q(out), "--to must be a finite number >= 0, got -1e-09"},
             {in + tf + " --ta nan -o " + q(out), "--ta must be a finite number >= 0"},
             {in + tf + " --fields pc,octree -o " + q(out), "octree not in {pc,acd,eacd}"},
             {in + tf + " --eacd-code log12 -o " + q(out), "log12 not in {log16,joint8,exact}"},
             {in + tf + " --trilinear --nearest -o " + q(out), "--trilinear excludes --nearest"},
             {in + " --tf " + q(dir / "none.json") + " -o " + q(out), "none.json"},
             {q(dir / "absent.raw") + tf + " -o " + q(out), "absent.raw"},
             {q(garbage) + tf + " -o " + q(out), garbage.string()},
             {in + tf + " -o " + q(dir / "missing" / "out.vprep"),
              "folder " + (dir / "missing").string() + " does not exist"},
             {in + tf + " -o " + q(dir), "it is a folder"},
             {in + tf, "--output is required"},
         }) {
        test::expectRefusal(volprep(c.args), "volprep", c.args, {c.message});
        EXPECT_FALSE(fs::exists(out));
        EXPECT_FALSE(fs::exists(dir / "missing"));
    }
}

TEST(VolprepCli, AFailedRunLeavesTheExistingOutputUntouched) {
    fs::path dir = test::scratchDir("volprep_keep");
    fs::path out = dir / "keep.vprep";
    ASSERT_EQ(volprep(headsqArgs(out) + " --fields pc").status, 0);
    std::string before = slurp(out);
    // Fails late, in the loader, after the flags were accepted.
    fs::path truncated = dir / "cut_64x64x93_uint16.raw.gz";
    std::string gz = slurp(test::datasetsDir() / headsq().file);
    std::ofstream(truncated, std::ios::binary).write(gz.data(), std::streamsize(gz.size() / 2));
    Outcome r = volprep(q(truncated) + " --tf " + q(test::datasetsDir() / headsq().tf) + " -o " + q(out));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(truncated.string()), std::string::npos) << r.err;
    EXPECT_EQ(slurp(out), before);
    // Nothing else was left in the folder (no temporary file).
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"cut_64x64x93_uint16.raw.gz", "keep.vprep"}));
}

}  // namespace
}  // namespace vr
