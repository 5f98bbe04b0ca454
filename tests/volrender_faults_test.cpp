// volrender against bad input and hostile conditions: absurd steps and sizes, unwritable outputs, missing and
// damaged prepared files, no Vulkan driver at all, a volume larger than the device allows, and a render killed
// while it writes its image. Every refusal exits non-zero with "volrender: <message>"; nothing hangs.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/prepared_file.h"
#include "support/cli.h"
#include "support/datasets.h"
#include "support/render_cases.h"
#include "render/image.h"
#include "volrender/vulkan/vulkan_context.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using test::shellQuote;

// A small prepared volume (no normals: renders use --no-shading): a block of opacity 0.3 in transparent air.
const fs::path& preparedBlock() {
    const GridGeometry grid{{12, 10, 8}, {1, 1, 2}, {0, 0, 0}};
    static const fs::path path = test::writtenSynthetic("volrender_faults_prepared", grid, 1.0, [](const Vec3i& v) {
        const bool inside = v.x > 2 && v.x < 9 && v.y > 1 && v.y < 8 && v.z > 1 && v.z < 6;
        return test::VoxelClass{inside ? 0.3 : 0.0, {0.9, 0.5, 0.2}};
    });
    return path;
}

test::CliOutcome volrender(const std::string& args, const std::string& env = "") {
    return test::runVolrender(args, env);
}

void expectRefused(const std::string& args, const std::vector<std::string>& mentions, const std::string& env = "") {
    test::expectRefusal(volrender(args, env), "volrender", args, mentions);
}
void expectRefused(const std::string& args, const std::string& mentions, const std::string& env = "") {
    expectRefused(args, std::vector<std::string>{mentions}, env);
}

TEST(VolrenderFaults, AbsurdStepsAreRefusedOrRenderedNeverHung) {
    const fs::path dir = test::scratchDir("volrender_faults_step");
    const std::string in =
        shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --size 8x8 --no-shading";
    // 1e-9: a valid number, but a ray would take more samples than the iteration cap.
    for (const char* step : {"0", "-0", "-1", "nan", "inf", "-inf", "1e-300", "1e-30", "1e-9"})
        for (const char* where : {" --cpu", ""}) expectRefused(in + where + " --step " + step, "--step");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    // A step far larger than the volume: one sample per ray, a valid image.
    for (const char* where : {" --cpu", ""}) {
        const test::CliOutcome r = volrender(in + where + " --step 1e9 --caster eacd --nearest");
        EXPECT_EQ(r.status, 0) << r.err;
        const Image image = readImage(dir / "x.png");
        EXPECT_EQ(image.width, 8);
        fs::remove(dir / "x.png");
    }
}

TEST(VolrenderFaults, ImpossibleSizesAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_size");
    const std::string in = shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --cpu --no-shading";
    for (const char* size : {"0x0", "0x8", "8x0", "-5x5", "100000x100000", "16385x1", "1x16385", "12x", "x12",
                             "8x8x8", "4294967304x8"})
        expectRefused(in + " --size " + size, "--size");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// The camera flags: malformed vectors (CLI11's refusals name the flag), a zero up or one along the view direction, a
// zoom that is no magnification, a focal point far off the volume; every refusal names its flag.
TEST(VolrenderFaults, BadCameraFlagsAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_camera");
    const std::string in =
        shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --cpu --no-shading --size 8x8";
    for (const char* up : {"1,2", "1,2,3,4", "a,b,c", "1,,2", "nan,0,1", "0,inf,0", "0,0,0", "0,0,1", "0,0,-3",
                           "1e-12,0,1"})
        expectRefused(in + " --up " + up, "--up");
    expectRefused(in + " --elevation 90 --up 0,1,0",
                  std::vector<std::string>{"--up", "parallel to the view direction"});
    for (const char* zoom : {"0", "-2", "nan", "inf", "1e-9", "1e9", "two"})
        expectRefused(in + " --zoom " + zoom, "--zoom");
    expectRefused(in + " --projection persp --fov 60 --zoom 0.3", std::vector<std::string>{"--zoom", "--fov"});
    for (const char* fov : {"0", "180", "-5", "nan"}) expectRefused(in + " --projection persp --fov " + fov, "--fov");
    // An orthographic camera has no field of view: --fov without --projection persp would change nothing.
    expectRefused(in + " --fov 45", std::vector<std::string>{"--fov", "--projection persp"});
    for (const char* background : {"1,2", "nan,0,0", "2,0,0", "0,-0.5,0", "0,0,a"})
        expectRefused(in + " --background " + background, "--background");
    for (const char* centre : {"1,2", "x,y,z", "nan,0,0", "0,0,-inf", "1e12,0,0"})
        expectRefused(in + " --center " + centre, "--center");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    // The Vulkan path refuses them too.
    expectRefused(shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --up 0,0,1", "--up");
    expectRefused(shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --center 1e12,0,0", "--center");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// Clipping flags: malformed planes and crops, a zero normal, more than six planes, a crop that is empty or reaches
// outside the grid (12 x 10 x 8 voxels); every refusal names its flag, and a good clipping renders.
TEST(VolrenderFaults, BadClippingFlagsAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_clip");
    const std::string in =
        shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --cpu --no-shading --size 8x8";
    for (const char* plane : {"1,2,3", "1,2,3,4,5", "a,b,c,d", "1,,2,3", "0,0,0,1", "nan,0,1,0", "0,1,0,inf", "1,0,0,"})
        expectRefused(in + " --clip " + plane, "--clip");
    std::string seven;
    for (int i = 0; i < 7; ++i) seven += " --clip 0,0,1," + std::to_string(i);
    expectRefused(in + seven, std::vector<std::string>{"--clip", "at most 6"});
    for (const char* crop : {"0,5,0,5,0", "0,5,0,5,0,5,0", "0,5.5,0,5,0,5", "a,5,0,5,0,5", "0,12,0,5,0,5",
                             "-1,5,0,5,0,5", "0,5,0,9,3,2", "20,30,0,5,0,5", "0,1e30,0,5,0,5"})
        expectRefused(in + " --crop " + crop, "--crop");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    const test::CliOutcome clipped = volrender(in + " --clip 1,0,0,4 --clip 0,1,1,5 --crop 0,11,2,7,0,3");
    EXPECT_EQ(clipped.status, 0) << clipped.err;
    EXPECT_TRUE(fs::exists(dir / "x.png"));
}

TEST(VolrenderFaults, BlendFlagsThatDoNotFitAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_blend");
    const std::string in =
        shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --size 8x8 --no-shading";
    for (const char* where : {" --cpu", ""}) {
        const std::string run = in + where;
        expectRefused(run + " --iso 100", std::vector<std::string>{"--iso", "--blend iso"});
        expectRefused(run + " --blend mip --iso 100", {"--iso", "--blend iso", "--blend mip"});
        expectRefused(run + " --blend iso", std::vector<std::string>{"--blend iso", "--iso VALUE"});
        expectRefused(run + " --blend maximum", {"--blend", "'maximum'", "composite, mip, minip, average or iso"});
        expectRefused(run + " --blend iso --iso nan", "--iso");
        expectRefused(run + " --blend mip --caster eacd", {"--caster eacd", "--blend mip", "--caster blocks"});
        expectRefused(run + " --caster blocks", std::vector<std::string>{"--caster blocks", "--blend composite"});
    }
    expectRefused(in + " --iso", "--iso");  // no value
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    // The same flags, fitting, render.
    for (const char* blend : {" --blend mip", " --blend minip --caster primitive", " --blend average --caster blocks",
                              " --blend iso --iso 1.5"}) {
        const test::CliOutcome r = volrender(in + " --cpu" + blend);
        EXPECT_EQ(r.status, 0) << blend << ": " << r.err;
    }
}

TEST(VolrenderFaults, GradientSourcesThatDoNotFitAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_gradients");
    const std::string in = shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --size 8x8";
    for (const char* where : {" --cpu", ""}) {
        expectRefused(in + where + " --gradients sobel", {"--gradients", "'sobel'", "on-the-fly or stored"});
        expectRefused(in + where + " --gradients stored --no-shading",
                      std::vector<std::string>{"--gradients stored", "--no-shading"});
        // Nor stored gradients, nor a light, where nothing is shaded.
        for (const char* blend : {"mip", "minip", "average"}) {
            expectRefused(in + where + " --gradients stored --blend " + blend,
                          std::vector<std::string>{"--gradients stored", blend, "not shaded"});
            expectRefused(in + where + " --light 1,0,0 --blend " + blend,
                          std::vector<std::string>{"--light", blend, "not shaded"});
        }
        expectRefused(in + where + " --light 1,0,0 --no-shading", std::vector<std::string>{"--light", "--no-shading"});
    }
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    for (const char* where : {" --cpu", ""}) {  // fitting, they render
        const test::CliOutcome r = volrender(in + where + " --gradients stored");
        EXPECT_EQ(r.status, 0) << where << ": " << r.err;
    }
}

TEST(VolrenderFaults, UnwritableOutputsAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_output");
    std::ofstream(dir / "plain.txt") << "a file, not a folder";
    fs::create_directory(dir / "folder.png");
    const std::string in = shellQuote(preparedBlock()) + " --cpu --no-shading --size 8x8 -o ";
    expectRefused(in + shellQuote(dir / "plain.txt" / "x.png"), "x.png");
    expectRefused(in + shellQuote(dir / "folder.png"), "folder.png");
    expectRefused(in + shellQuote(dir / "absent" / "x.png"), "does not exist");
    expectRefused(in + "/sys/volrender_faults.png", "volrender_faults.png");  // a read-only file system
    expectRefused(in + "/proc/volrender_faults.png", "volrender_faults.png");  // no regular files can be made
    expectRefused(in + shellQuote(dir / "x.png") + " --stats " + shellQuote(dir / "plain.txt" / "s.json"), "s.json");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    // Root passes the writability check on /sys, so this heat map fails only after the image was written: the run
    // still exits non-zero naming the heat map.
    expectRefused(in + shellQuote(dir / "y.png") + " --heatmap /sys/heat.png", "heat.png");
}

// Two outputs at one path, or an output at an input's: refused before anything is written, naming both flags; the
// input is left as it was.
TEST(VolrenderFaults, OutputsOverAnotherFileAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_same_file");
    const fs::path input = dir / "block.vprep";
    fs::copy_file(preparedBlock(), input);
    const std::string source = test::slurp(input);
    const std::string in = shellQuote(input) + " --cpu --no-shading --size 8x8";
    const std::string x = shellQuote(dir / "x.png");
    expectRefused(in + " -o " + x + " --heatmap " + x, std::vector<std::string>{"-o and --heatmap", "x.png"});
    expectRefused(in + " -o " + x + " --stats " + x, std::vector<std::string>{"-o and --stats", "x.png"});
    // The same file by another spelling of its path.
    expectRefused(in + " -o " + x + " --stats " + shellQuote(dir / "." / "x.png"), "-o and --stats");
    expectRefused(in + " -o " + x + " --stats " + shellQuote(input),
                  std::vector<std::string>{"the input and --stats", "would write over the input"});
    // The names an orbit or a pair derives from -o and --heatmap: their frames and eyes.
    expectRefused(in + " -o " + x + " --views 2 --stats " + shellQuote(dir / "x_001.png"),
                  std::vector<std::string>{"-o and --stats", "x_001.png", "-o " + (dir / "x.png").string()});
    expectRefused(in + " -o " + x + " --views 3 --heatmap " + x, std::vector<std::string>{"-o and --heatmap", "x_000"});
    const std::string pair = " --projection persp --stereo 1 -o " + x;
    expectRefused(in + pair + " --stats " + shellQuote(dir / "x_left.png"),
                  std::vector<std::string>{"-o and --stats", "x_left.png"});
    expectRefused(in + pair + " --views 2 --heatmap " + shellQuote(dir / "x_right_001.png") + " --stats " +
                      shellQuote(dir / "x_right_001_left_001.png"),
                  std::vector<std::string>{"--heatmap and --stats", "x_right_001_left_001.png"});
    EXPECT_EQ(test::slurp(input), source);
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "only the input is there";
}

// The prepared file's parts, to damage one at a time (docs/PREPARED_FORMAT.md).
struct PreparedBytes {
    std::string bytes;
    uint64_t headerBytes() const {
        uint64_t h;
        std::memcpy(&h, bytes.data() + 12, 8);
        return h;
    }
    nlohmann::json header() const { return nlohmann::json::parse(bytes.substr(20, headerBytes())); }
    // Replaces the header text, with a correct checksum (so that only the content is wrong).
    std::string withHeaderText(const std::string& text) const {
        std::string out = bytes.substr(0, 12);
        const uint64_t h = text.size();
        out.append(reinterpret_cast<const char*>(&h), 8);
        out += text;
        const uint32_t crc = uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(text.data()), uInt(text.size())));
        out.append(reinterpret_cast<const char*>(&crc), 4);
        out += bytes.substr(24 + headerBytes());
        return out;
    }
    std::string withHeader(const std::function<void(nlohmann::json&)>& edit) const {
        nlohmann::json h = header();
        edit(h);
        return withHeaderText(h.dump(1));
    }
};

TEST(VolrenderFaults, MissingAndDamagedPreparedFilesAreRefused) {
    const fs::path dir = test::scratchDir("volrender_faults_damaged");
    const PreparedBytes good{test::slurp(preparedBlock())};
    const uint64_t h = good.headerBytes();
    ASSERT_EQ(good.withHeaderText(good.bytes.substr(20, h)), good.bytes);  // the rewriting is faithful

    std::vector<std::pair<std::string, std::string>> damaged;  // bytes, what the message must say
    auto add = [&](std::string bytes, std::string says) { damaged.emplace_back(std::move(bytes), std::move(says)); };
    std::string b = good.bytes;
    b[0] = 'X';
    add(b, "not a prepared file");
    // 1: before coded EACD (core/extent_code.h); 2: before the scalars and the transfer table replaced the classified
    // arrays; 3: before the chunks were compressed.
    for (uint32_t version : {0u, 1u, 2u, 3u, 4u, uint32_t(kPreparedFormatVersion) + 1, 0xffffffffu}) {
        b = good.bytes;
        std::memcpy(b.data() + 8, &version, 4);
        add(b, "version " + std::to_string(version));
    }
    for (uint64_t length : {uint64_t(0), uint64_t(7), uint64_t(19), 20 + h / 2, 24 + h, uint64_t(good.bytes.size() / 2),
                            uint64_t(good.bytes.size() - 1)})
        add(good.bytes.substr(0, length), length < 20 ? "not a prepared file" : "truncated");
    b = good.bytes;
    b[20 + h / 2] ^= 0x20;  // header text changed, checksum not
    add(b, "header checksum mismatch");
    b = good.bytes;
    b[24 + h + 5] ^= 0x01;  // the first chunk's data (the scalars, read by every render)
    add(b, "checksum mismatch");
    uint64_t hugeHeader = uint64_t(1) << 40;
    b = good.bytes;
    std::memcpy(b.data() + 12, &hugeHeader, 8);
    add(b, "header length");
    add(good.withHeaderText("{ not json"), "bad header");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["dims"] = {2, 2, 2}; }), "needs");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["dims"] = {0, 10, 8}; }), "absurd grid dims");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["dims"] = {100000, 10, 8}; }), "absurd grid dims");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["dims"] = {12, 10}; }), "dims");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["dims"] = {12.5, 10, 8}; }), "absurd grid dims");
    // (A count below the labels' ids is refused where the labels are read, tests/io_prepared_file_test.cpp: a render
    // reads no region labels.)
    add(good.withHeader([](nlohmann::json& j) { j["regionCount"] = -1; }), "regionCount");
    add(good.withHeader([](nlohmann::json& j) { j.erase("chunks"); }), "chunks");
    add(good.withHeader([](nlohmann::json& j) { j["chunks"].erase(0); }), "has no 'scalars' chunk");
    add(good.withHeader([](nlohmann::json& j) { j["chunks"][0]["offset"] = uint64_t(1) << 62; }), "truncated");
    add(good.withHeader([](nlohmann::json& j) { j["chunks"][1]["bytes"] = 12; }), "needs");
    add(good.withHeader([](nlohmann::json& j) { j["chunks"][0]["type"] = "float64"; }), "chunk 'scalars' should be");
    add(good.withHeader([](nlohmann::json& j) { j["chunks"].push_back(j["chunks"][0]); }), "twice");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["spacing"] = {0, 1, 2}; }), "spacing");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["spacing"] = {1, -1, 2}; }), "spacing");
    add(good.withHeader([](nlohmann::json& j) { j["grid"]["spacing"] = {1, 1, 1e308}; }), "spacing");
    add(good.withHeader([](nlohmann::json& j) { j["metadata"]["distanceCap"] = 1000; }), "distanceCap");

    for (std::size_t i = 0; i < damaged.size(); ++i) {
        const auto& [bytes, says] = damaged[i];
        const fs::path file = dir / ("damaged_" + std::to_string(i) + ".vprep");
        std::ofstream(file, std::ios::binary) << bytes;
        // EACD reads the scalars, the table and its views' octants. A damaged file is refused as it is read, before
        // any render, so the CPU path stands for the Vulkan one, which is run on the first file only.
        const std::string args = shellQuote(file) + " -o " + shellQuote(dir / "x.png") + " --size 8x8 --no-shading";
        SCOPED_TRACE(file.filename().string() + " expecting '" + says + "'");
        expectRefused(args + " --cpu --caster eacd", {says, file.filename().string()});
        if (i == 0) expectRefused(args + " --caster eacd", {says, file.filename().string()});
    }
    std::printf("damaged prepared files: %zu\n", damaged.size());
    expectRefused(shellQuote(dir / "absent.vprep") + " -o " + shellQuote(dir / "x.png") + " --cpu", "absent.vprep");
    expectRefused(shellQuote(dir) + " -o " + shellQuote(dir / "x.png") + " --cpu", dir.filename().string());
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(VolrenderFaults, NoVulkanDriverIsAClearErrorAndTheCpuStillRenders) {
    const fs::path dir = test::scratchDir("volrender_faults_nodevice");
    const std::string env = "VK_ICD_FILENAMES=/nonexistent/no_icd.json VK_DRIVER_FILES=/nonexistent/no_icd.json";
    const std::string in =
        shellQuote(preparedBlock()) + " -o " + shellQuote(dir / "x.png") + " --size 8x8 --no-shading";
    expectRefused(in, "Vulkan", env);
    expectRefused("--list-devices", "Vulkan", env);
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    const test::CliOutcome cpu = volrender(in + " --cpu", env);
    EXPECT_EQ(cpu.status, 0) << cpu.err;
    EXPECT_TRUE(fs::exists(dir / "x.png"));
}

TEST(VolrenderFaults, VolumeLargerThanTheDeviceAllowsRendersInBricks) {
    const int limit = [] {
        VulkanContext ctx;
        return int(ctx.physicalDevice().getProperties().limits.maxImageDimension3D);
    }();
    ASSERT_LT(limit, 1 << 16) << "the prepared format's largest dimension fits this device";
    const fs::path dir = test::scratchDir("volrender_faults_limit");
    const GridGeometry grid{{1, 1, limit + 1}, {1, 1, 1}, {0, 0, 0}};
    writePrepared(dir / "long.vprep", test::syntheticPrepared(grid, 1.0, [](const Vec3i& v) {
                      return test::VoxelClass{v.z % 7 ? 0.0 : 0.5, {1, 1, 1}};
                  }));
    const std::string in = shellQuote(dir / "long.vprep") + " -o " + shellQuote(dir / "x.png") +
                           " --size 8x8 --no-shading --azimuth 90";
    const test::CliOutcome gpu = volrender(in + " --stats " + shellQuote(dir / "stats.json"));
    EXPECT_EQ(gpu.status, 0) << gpu.err;
    EXPECT_TRUE(fs::exists(dir / "x.png"));
    // The stats name the bricks and their bytes: the scalars (uint16, 2 bytes a voxel) of each brick's image.
    const nlohmann::json upload = nlohmann::json::parse(std::ifstream(dir / "stats.json"))["upload"];
    ASSERT_GE(upload["bricks"].size(), 2u);
    std::size_t bytes = 0;
    for (const auto& b : upload["bricks"]) bytes += b["bytes"]["scalars"].get<std::size_t>();
    EXPECT_EQ(bytes, upload["bytes"]["scalars"].get<std::size_t>());
    EXPECT_GT(bytes, grid.voxels() * 2);  // two voxels of overlap each side of every cut
    const test::CliOutcome cpu = volrender(in + " --cpu");  // the CPU reference has no such limit
    EXPECT_EQ(cpu.status, 0) << cpu.err;
}

// SIGKILL in the middle of writing a large image: the previous image is intact under the output name, and
// whatever the killed run left is a hidden temporary, not the output.
TEST(VolrenderFaults, KilledWhileWritingLeavesThePreviousImage) {
    const fs::path dir = test::scratchDir("volrender_faults_kill");
    const fs::path out = dir / "big.exr";
    const std::string small = shellQuote(preparedBlock()) + " -o " + shellQuote(out) + " --cpu --no-shading --size 8x8";
    ASSERT_EQ(volrender(small).status, 0);
    const std::string before = test::slurp(out);
    ASSERT_FALSE(before.empty());
    const bool killed = test::killWhileWriting(
        test::volrenderExecutable(),
        {preparedBlock().string(), "-o", out.string(), "--cpu", "--no-shading", "--size", "3000x3000"}, dir,
        ".big.tmp", 120);
    EXPECT_TRUE(killed) << "the render ended before its temporary image appeared";
    EXPECT_EQ(test::slurp(out), before);
    EXPECT_EQ(readImage(out).width, 8);
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "big.exr" || name.rfind(".big.tmp", 0) == 0) << name;
    }
    // The next write of the same output removes what the killed run left.
    ASSERT_EQ(volrender(small).status, 0);
    for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "big.exr");
}

}  // namespace
}  // namespace vr
