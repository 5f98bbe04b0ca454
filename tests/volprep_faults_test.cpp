// volprep against bad input and hostile conditions: flags it does not have (--step belongs to volrender),
// absurd spacing, thresholds, dims and transfer-function flags, unwritable outputs, and a run killed while it
// writes the prepared file.
// Every refusal exits non-zero with "volprep: <message>" and writes nothing.
#include <gtest/gtest.h>

#include <fstream>

#include "io/prepared_file.h"
#include "support/cli.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using test::shellQuote;

constexpr auto volprep = [](const std::string& args) { return test::runVolprep(args); };

void expectRefused(const std::string& args, const std::string& mentions) {
    test::expectRefusal(volprep(args), "volprep", args, {mentions});
}

// A small raw volume named so that volprep knows its dims and type: a bright block in a dark box.
fs::path smallRaw(const fs::path& dir) {
    const fs::path raw = dir / "block_8x6x5_uint8.raw";
    std::string bytes(8 * 6 * 5, char(10));
    for (int i = 40; i < 200; i += 3) bytes[i] = char(220);
    std::ofstream(raw, std::ios::binary) << bytes;
    return raw;
}

const std::string kTf = " --tf " + shellQuote(test::datasetsDir() / "sim.tf.json");

TEST(VolprepFaults, StepIsNotAVolprepFlag) {
    const fs::path dir = test::scratchDir("volprep_faults_step");
    const std::string in = shellQuote(smallRaw(dir)) + kTf + " -o " + shellQuote(dir / "x.vprep");
    for (const char* step : {"0", "-1", "nan", "1e9"}) {
        const test::CliOutcome r = volprep(in + " --step " + step);
        EXPECT_EQ(r.status, 2) << step;
        EXPECT_EQ(r.err.rfind("volprep: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find("--step"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "x.vprep"));
}

TEST(VolprepFaults, AbsurdSpacingThresholdsAndDimsAreRefused) {
    const fs::path dir = test::scratchDir("volprep_faults_numbers");
    const std::string in = shellQuote(smallRaw(dir)) + kTf + " -o " + shellQuote(dir / "x.vprep");
    for (const char* spacing : {"0,1,1", "1,-1,1", "nan,1,1", "1,inf,1", "1,1,1e309", "1e300,1e300,1e300"})
        expectRefused(in + " --spacing " + spacing, "spacing");
    // Positive and finite but absurd: the TF's opacity per smallest spacing would be an infinite extinction.
    expectRefused(in + " --spacing 1e-320,1,1", "spacing");
    for (const char* to : {"nan", "-1", "inf", "-inf"}) expectRefused(in + " --to " + to, "--to");
    for (const char* ta : {"nan", "-0.5", "inf"}) expectRefused(in + " --ta " + ta, "--ta");
    // Flags the preparation would not use: a normal angle for regions without normals, a code for a field not built.
    expectRefused(in + " --no-normals --ta 5", "--ta 5");
    expectRefused(in + " --fields pc,acd --eacd-code exact", "--eacd-code exact");
    const fs::path anonymous = dir / "anonymous.bin";
    std::ofstream(anonymous, std::ios::binary) << std::string(64, 'a');
    for (const char* dims : {"0x4x4", "4x4x-4", "100000x100000x100000", "65537x1x1"})
        expectRefused(
            shellQuote(anonymous) + kTf + " --type uint8 --dims " + dims + " -o " + shellQuote(dir / "x.vprep"),
            "anonymous.bin");
    EXPECT_FALSE(fs::exists(dir / "x.vprep"));
}

// The transfer-function flags: an unknown preset gets the list of presets; a window that is not a finite number
// above 0 or a level that is not finite is refused before the volume is read; one without the other, or none of
// them, is a bad command line.
TEST(VolprepFaults, BadTransferFlagsAreRefused) {
    const fs::path dir = test::scratchDir("volprep_faults_transfer");
    const std::string in = shellQuote(smallRaw(dir)) + " -o " + shellQuote(dir / "x.vprep");
    expectRefused(in + " --tf CT-Bon", "--tf CT-Bon: no such file, nor a built-in preset of that name (the presets: "
                                       "CT-AAA, CT-Bone, CT-Cardiac, CT-Lung, CT-Muscle, CT-Soft-Tissue, MR-Angio, "
                                       "MR-Default, MR-T2-Brain; --list-presets describes them)");
    for (const char* window : {"0", "-0", "-400", "nan", "inf", "-inf"})
        expectRefused(in + " --level 40 --window " + window, std::string("--window ") + window);
    for (const char* level : {"nan", "inf", "-inf"})
        expectRefused(in + " --window 400 --tf CT-Bone --level " + level, std::string("--level ") + level);
    expectRefused(in + " --window 1 --level 1e20", "not two distinct finite numbers");
    for (const auto& [flags, message] : {std::pair{" --window 400", "--window requires --level"},
                                         {" --tf CT-Bone --level 40", "--level requires --window"},
                                         {"", "At least 1 option from [--tf,--window,--level] is required"}}) {
        const test::CliOutcome r = volprep(in + flags);
        EXPECT_EQ(r.status, 2) << flags;
        test::expectRefusal(r, "volprep", in + flags, {message});
    }
    EXPECT_FALSE(fs::exists(dir / "x.vprep"));
}

TEST(VolprepFaults, UnwritableOutputsAreRefused) {
    const fs::path dir = test::scratchDir("volprep_faults_output");
    std::ofstream(dir / "plain.txt") << "a file, not a folder";
    fs::create_directory(dir / "folder.vprep");
    const std::string in = shellQuote(smallRaw(dir)) + kTf + " -o ";
    expectRefused(in + shellQuote(dir / "plain.txt" / "x.vprep"), "x.vprep");
    expectRefused(in + shellQuote(dir / "folder.vprep"), "folder.vprep");
    expectRefused(in + shellQuote(dir / "absent" / "x.vprep"), "does not exist");
    expectRefused(in + "/sys/volprep_faults.vprep", "volprep_faults.vprep");   // a read-only file system
    expectRefused(in + "/proc/volprep_faults.vprep", "volprep_faults.vprep");  // no regular files can be made
    // A prepared file named as a volume (which could replace the source) or an image is refused, the input untouched.
    const std::string source = test::slurp(smallRaw(dir));
    for (const char* name : {"block_8x6x5_uint8.raw", "x.nii.gz", "x.NRRD", "x.png", "x.EXR", "x.mp4"})
        expectRefused(in + shellQuote(dir / name), name);
    EXPECT_EQ(test::slurp(dir / "block_8x6x5_uint8.raw"), source);
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// SIGKILL in the middle of writing a large prepared file: the previous file is intact and still reads, and what
// the killed run left is a hidden temporary, not the output.
TEST(VolprepFaults, KilledWhileWritingLeavesThePreviousFile) {
    const fs::path dir = test::scratchDir("volprep_faults_kill");
    const fs::path out = dir / "shells.vprep";
    const fs::path small = smallRaw(dir);
    ASSERT_EQ(volprep(shellQuote(small) + kTf + " -o " + shellQuote(out)).status, 0);
    const std::string before = test::slurp(out);

    const std::string phantom = shellQuote(test::volphantomExecutable()) + " shells --dims 160x160x160 -o " +
                                shellQuote(dir) + " >/dev/null";
    ASSERT_EQ(std::system(phantom.c_str()), 0);
    const fs::path big = dir / "shells_160x160x160_int16.raw";
    ASSERT_TRUE(fs::exists(big));
    const bool killed = test::killWhileWriting(
        test::volprepExecutable(),
        {big.string(), "--tf", (test::datasetsDir() / "cranium_ct.tf.json").string(), "--fields", "pc", "-o",
         out.string()},
        dir, ".shells.tmp", 120);
    EXPECT_TRUE(killed) << "volprep ended before its temporary file appeared";
    EXPECT_EQ(test::slurp(out), before);
    EXPECT_EQ(readPrepared(out).grid().dims, (Vec3i{8, 6, 5}));
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "shells.vprep" || name == small.filename() || name == big.filename() ||
                    name.rfind(".shells.tmp", 0) == 0)
            << name;
    }
    // The next write of the same output removes what the killed run left.
    ASSERT_EQ(volprep(shellQuote(small) + kTf + " -o " + shellQuote(out)).status, 0);
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_NE(entry.path().filename().string().rfind(".shells.tmp", 0), 0u) << entry.path();
}

}  // namespace
}  // namespace vr
