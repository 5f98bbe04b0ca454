// volrender end to end on a prepared head CT: images, heat maps, statistics, orbits, the CPU path, and every
// bad input exiting non-zero with "volrender: <message>" on stderr.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "io/caster_calibration_file.h"
#include "io/prepared_file.h"
#include "render/caster_choice.h"
#include "render/image.h"
#include "support/cli.h"
#include "support/load_dataset.h"
#include "support/prepare.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

using test::slurp;
constexpr auto volrender = [](const std::string& args) { return test::runVolrender(args); };
constexpr auto q = test::shellQuote;

// vtk_headsq_ct with its transfer function and spacing, thresholds (0.02, 10 deg), regions for trilinear sampling
// (volrender's default), every field: prepared once.
const fs::path& preparedHead() {
    static const fs::path path = [] {
        const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
        const PreparedVolume p = test::prepareVolume(test::loadDataset(e), test::datasetTransferFunction(e.tf),
                                                     {0.02, 10, true, true});
        const fs::path out = test::scratchDir("volrender_cli_prepared") / "headsq.vrp";
        writePrepared(out, p);
        return out;
    }();
    return path;
}

TEST(VolrenderCli, RendersImageHeatmapAndStatistics) {
    const fs::path dir = test::scratchDir("volrender_cli_render");
    const test::CliOutcome r =
        volrender(q(preparedHead()) + " -o " + q(dir / "head.png") + " --caster eacd --size 64x48" +
                  " --azimuth 30 --elevation 10 --stats " + q(dir / "stats.json") + " --heatmap " +
                  q(dir / "heat.png"));
    ASSERT_EQ(r.status, 0) << r.err;
    const Image image = readImage(dir / "head.png");
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 48);
    EXPECT_EQ(readImage(dir / "heat.png").width, 64);

    const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "stats.json"));
    EXPECT_EQ(stats["settings"]["caster"], "eacd");
    const auto& view = stats["views"][0];
    EXPECT_GT(view["iterationsPerRay"]["mean"].get<double>(), 0);
    EXPECT_GE(view["iterationsPerRay"]["max"].get<double>(), view["iterationsPerRay"]["p95"].get<double>());
    EXPECT_GT(view["samplesRepresented"]["total"].get<double>(), 0);
    EXPECT_GE(view["deviceMs"].get<double>(), 0);
    EXPECT_GT(view["wallMs"].get<double>(), 0);
    // One octant of EACD (4 bytes a voxel, exact), the scalars as the source holds them (uint16) and the transfer
    // table: nothing else, shaded or not.
    const std::size_t voxels = 64 * 64 * 93;
    EXPECT_EQ(view["uploadedBytes"]["eacd"].get<std::size_t>(), voxels * 4);
    EXPECT_EQ(view["uploadedBytes"]["scalars"].get<std::size_t>(), voxels * 2);
    EXPECT_GT(view["uploadedBytes"]["table"].get<std::size_t>(), 0u);
    EXPECT_EQ(view["uploadedBytes"].size(), 3u);
    const nlohmann::json& perVoxel = stats["upload"]["bytesPerVoxel"];
    EXPECT_EQ(perVoxel["scalars"].get<double>(), 2.0);
    EXPECT_EQ(perVoxel["eacd"].get<double>(), 4.0);
    EXPECT_DOUBLE_EQ(stats["upload"]["bytesPerVoxelTotal"].get<double>(), 6.0 + perVoxel["table"].get<double>());
}

TEST(VolrenderCli, VulkanAndCpuImagesAgree) {
    const fs::path dir = test::scratchDir("volrender_cli_cpu");
    const std::string common = " --caster acd --size 40x32 --projection persp --azimuth -50 --no-shading";
    ASSERT_EQ(volrender(q(preparedHead()) + " -o " + q(dir / "gpu.exr") + common).status, 0);
    ASSERT_EQ(volrender(q(preparedHead()) + " -o " + q(dir / "cpu.exr") + common + " --cpu").status, 0);
    EXPECT_LT(maxAbsDifference(readImage(dir / "gpu.exr"), readImage(dir / "cpu.exr")), 1e-3);
}

TEST(VolrenderCli, OrbitWritesNumberedViews) {
    const fs::path dir = test::scratchDir("volrender_cli_orbit");
    const test::CliOutcome r =
        volrender(q(preparedHead()) + " -o " + q(dir / "orbit.png") + " --caster pc --size 24x24 --views 3");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* name : {"orbit_000.png", "orbit_001.png", "orbit_002.png"})
        EXPECT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_FALSE(fs::exists(dir / "orbit.png"));
    // Each view's line gives its times; its rays are counted only where an output shows them.
    EXPECT_NE(r.out.find("ms wall"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("iterations per ray"), std::string::npos) << r.out;
    const test::CliOutcome counted = volrender(q(preparedHead()) + " -o " + q(dir / "orbit.png") +
                                               " --caster pc --size 24x24 --heatmap " + q(dir / "heat.png"));
    ASSERT_EQ(counted.status, 0) << counted.err;
    EXPECT_NE(counted.out.find("iterations per ray"), std::string::npos) << counted.out;
}

TEST(VolrenderCli, HelpAndDeviceList) {
    const test::CliOutcome help = volrender("--help");
    EXPECT_EQ(help.status, 0);
    for (const char* flag :
         {"--caster", "--calibration", "--size", "--stats", "--heatmap", "--views", "--cpu", "--trilinear", "--nearest",
          "--tf", "--window", "--level", "--list-presets", "--up", "--center", "--zoom", "--fps", ".mp4", "--clip",
          "--crop", "--blend", "--iso", "hier"})
        EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
    const test::CliOutcome list = volrender("--list-devices");
    EXPECT_EQ(list.status, 0);
    EXPECT_EQ(list.out.rfind("0: ", 0), 0u) << list.out;
}

void expectRejected(const std::string& args, const std::string& mentions) {
    test::expectRefusal(volrender(args), "volrender", args, {mentions});
}

TEST(VolrenderCli, BadInputsExitWithReadableErrors) {
    const fs::path dir = test::scratchDir("volrender_cli_bad");
    const std::string in = q(preparedHead()), out = " -o " + q(dir / "x.png");
    expectRejected(in + out + " --step 0", "--step 0: the step must be");
    expectRejected(in + out + " --step nan", "--step");
    expectRejected(in + out + " --size 0x0", "--size");
    expectRejected(in + out + " --size 100000x100000", "--size");
    expectRejected(in + out + " --size banana", "--size");
    expectRejected(in + out + " --caster fast", "unknown caster");
    expectRejected(in + out + " --ert 0", "--ert 0: must be in (0, 1]");
    expectRejected(in + out + " --projection fisheye", "--projection");
    expectRejected(in + out + " --light 0,0,0", "--light");
    expectRejected(in + " -o " + q(dir / "missing" / "x.png"), "does not exist");
    expectRejected(q(dir / "nothing.vrp") + out, "nothing.vrp");
    std::ofstream(dir / "garbage.vrp") << "not a prepared volume";
    expectRejected(q(dir / "garbage.vrp") + out, "garbage.vrp");
    expectRejected(in + out + " --device 99", "device 99");
    expectRejected(in + out + " --trilinear --nearest", "--trilinear excludes --nearest");
    expectRejected(in + out + " --cpu --device 0", "--device excludes --cpu");  // the CPU reference is no device
    expectRejected(in + out + " --cpu --calibration c.json", "--calibration excludes --cpu");  // nor priced
    const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
    expectRejected(q(test::datasetsDir() / e.file) + " --tf " + q(test::datasetsDir() / e.tf) + out +
                       " --no-shading --ta 5",
                   "--ta 5: the regions are made without normals");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// The head CT prepared into dir/head.vrp with `regions`, and the arguments that render it there into x.png, 16 x 16,
// with the stats in s.json.
std::string headsqPreparedRun(const fs::path& dir, const SegmentationParams& regions) {
    const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
    writePrepared(dir / "head.vrp",
                  test::prepareVolume(test::loadDataset(e), test::datasetTransferFunction(e.tf), regions));
    return q(dir / "head.vrp") + " -o " + q(dir / "x.png") + " --size 16x16 --stats " + q(dir / "s.json");
}

// Regions made for nearest sampling only: trilinear sampling (the default) cannot leap through them. A caster that
// leaps through them asked for is refused with the reason (hier, which makes its own blocks, is not); auto takes the
// primitive caster and says why; --nearest leaps.
TEST(VolrenderCli, TrilinearByDefaultAndRegionsMadeForNearestSampling) {
    const fs::path dir = test::scratchDir("volrender_cli_nearest");
    const std::string run = headsqPreparedRun(dir, {0.02, 10, true, false});
    expectRejected(run + " --caster eacd", "segmented for trilinear sampling");
    // The hier caster builds its blocks from the scalars at load, each with its voxels' footprints: any file serves.
    const test::CliOutcome hier = volrender(run + " --caster hier");
    ASSERT_EQ(hier.status, 0) << hier.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(dir / "s.json"))["settings"]["caster"], "hier");
    const test::CliOutcome chosen = volrender(run);
    ASSERT_EQ(chosen.status, 0) << chosen.err;
    nlohmann::json stats = nlohmann::json::parse(slurp(dir / "s.json"));
    EXPECT_EQ(stats["settings"]["caster"], "primitive");
    EXPECT_EQ(stats["settings"]["trilinear"], true);
    EXPECT_EQ(stats["settings"]["shading"], true);
    EXPECT_NE(stats["settings"]["casterChoice"].get<std::string>().find("nearest sampling only"), std::string::npos);
    ASSERT_EQ(volrender(run + " --caster eacd --nearest").status, 0);
    stats = nlohmann::json::parse(slurp(dir / "s.json"));
    EXPECT_EQ(stats["settings"]["trilinear"], false);
}

// Regions made without normals (volprep --no-normals) cannot carry a shade: auto takes the primitive caster for a
// shaded render and says why; an unshaded render may leap.
TEST(VolrenderCli, AutoShadesRegionsMadeWithoutNormalsSampleBySample) {
    const fs::path dir = test::scratchDir("volrender_cli_no_normals");
    const std::string run = headsqPreparedRun(dir, {0.02, 10, false, true});
    const test::CliOutcome shaded = volrender(run);
    ASSERT_EQ(shaded.status, 0) << shaded.err;
    nlohmann::json stats = nlohmann::json::parse(slurp(dir / "s.json"));
    EXPECT_EQ(stats["settings"]["caster"], "primitive");
    EXPECT_NE(stats["settings"]["casterChoice"].get<std::string>().find("without normals"), std::string::npos);
    ASSERT_EQ(volrender(run + " --no-shading").status, 0);
    stats = nlohmann::json::parse(slurp(dir / "s.json"));
    EXPECT_EQ(stats["settings"]["casterChoice"].get<std::string>().find("without normals"), std::string::npos);
    const test::CliOutcome leaping = volrender(run + " --no-shading --caster eacd");
    EXPECT_EQ(leaping.status, 0) << leaping.err;
}

// One command from a volume file to an image: prepared in memory as volprep prepares it, so the image is the one
// rendered from volprep's file with the same caster.
TEST(VolrenderCli, RendersAVolumeFileInOneCommand) {
    const fs::path dir = test::scratchDir("volrender_cli_one_command");
    const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
    const std::string volume = q(test::datasetsDir() / e.file), tf = " --tf " + q(test::datasetsDir() / e.tf);
    const std::string view = " --size 48x40 --azimuth 30 --elevation 20";
    const test::CliOutcome one = volrender(volume + tf + view + " --caster eacd -o " + q(dir / "one.exr") +
                                           " --stats " + q(dir / "one.json"));
    ASSERT_EQ(one.status, 0) << one.err;
    const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "one.json"));
    EXPECT_EQ(stats["settings"]["caster"], "eacd");
    for (const char* stage : {"load", "classify", "segment", "eacd"})
        EXPECT_GE(stats["prepareSeconds"][stage].get<double>(), 0.0) << stage;
    EXPECT_FALSE(stats["prepareSeconds"].contains("pc"));  // only the field of the caster ...
    EXPECT_EQ(stats["upload"]["bytesPerVoxel"]["eacd"].get<double>(), 2.0);  // ... in the view's octant (log16)
    // The process's peak: at least the float scalars it loaded, less than the test machine's memory.
    EXPECT_GT(stats["peakResidentBytes"].get<double>(), 4.0 * 64 * 64 * 93);
    EXPECT_LT(stats["peakResidentBytes"].get<double>(), 64e9);
    // Where the process's time went: the device opened, then the volume was uploaded, then the image written.
    const nlohmann::json& timeline = stats["timelineMs"];
    for (const char* milestone :
         {"deviceOpened", "rendererMade", "volumeReady", "uploaded", "firstViewRendered", "imagesWritten"})
        ASSERT_TRUE(timeline.contains(milestone)) << milestone;
    EXPECT_GT(timeline["deviceOpened"].get<double>(), 0.0);
    EXPECT_LE(timeline["deviceOpened"].get<double>(), timeline["uploaded"].get<double>());
    EXPECT_LE(timeline["volumeReady"].get<double>(), timeline["uploaded"].get<double>());
    EXPECT_LT(timeline["uploaded"].get<double>(), timeline["firstViewRendered"].get<double>());
    EXPECT_LE(timeline["firstViewRendered"].get<double>(), timeline["imagesWritten"].get<double>());

    ASSERT_EQ(test::runVolprep(volume + tf + " --fields eacd -o " + q(dir / "head.vprep")).status, 0);
    ASSERT_EQ(volrender(q(dir / "head.vprep") + view + " --caster eacd -o " + q(dir / "file.exr")).status, 0);
    EXPECT_EQ(maxAbsDifference(readImage(dir / "one.exr"), readImage(dir / "file.exr")), 0.0f);

    expectRejected(volume + view + " -o " + q(dir / "x.png"), "needs --tf");
    expectRejected(q(dir / "head.vprep") + tf + " -o " + q(dir / "x.png"),
                   "a prepared file holds its transfer function");
    expectRejected(volume + tf + " --to -1 -o " + q(dir / "x.png"), "--to");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// The hier caster in one command builds its field from the scalars without segmenting any voxel, uploads a field
// of blocks, and renders what it renders from a prepared file of the same volume (its field built at load); at
// thresholds 0 the primitive caster's image.
TEST(VolrenderCli, HierRendersWithoutSegmentingHereAndFromAPreparedFile) {
    const fs::path dir = test::scratchDir("volrender_cli_hier");
    const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
    const std::string volume = q(test::datasetsDir() / e.file), tf = " --tf " + q(test::datasetsDir() / e.tf);
    const std::string view = " --size 48x40 --azimuth 30 --elevation 20";
    const test::CliOutcome one = volrender(volume + tf + view + " --caster hier -o " + q(dir / "one.exr") +
                                           " --stats " + q(dir / "one.json"));
    ASSERT_EQ(one.status, 0) << one.err;
    const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "one.json"));
    EXPECT_EQ(stats["settings"]["caster"], "hier");
    EXPECT_GE(stats["prepareSeconds"]["hier"].get<double>(), 0.0);
    EXPECT_FALSE(stats["prepareSeconds"].contains("segment"));
    // 16 x 16 x 24 blocks of 4^3 voxels, 2 bytes each in the view's one octant.
    EXPECT_EQ(stats["views"][0]["uploadedBytes"]["hier"].get<std::size_t>(), 16u * 16 * 24 * 2);

    ASSERT_EQ(test::runVolprep(volume + tf + " --fields eacd -o " + q(dir / "head.vprep")).status, 0);
    const test::CliOutcome file = volrender(q(dir / "head.vprep") + view + " --caster hier -o " + q(dir / "file.exr"));
    ASSERT_EQ(file.status, 0) << file.err;
    EXPECT_EQ(maxAbsDifference(readImage(dir / "one.exr"), readImage(dir / "file.exr")), 0.0f);

    const std::string exact = volume + tf + view + " --to 0 --ta 0 -q -o ";
    ASSERT_EQ(volrender(exact + q(dir / "hier0.exr") + " --caster hier").status, 0);
    ASSERT_EQ(volrender(exact + q(dir / "primitive0.exr") + " --caster primitive").status, 0);
    EXPECT_LT(maxAbsDifference(readImage(dir / "hier0.exr"), readImage(dir / "primitive0.exr")), 1e-4);
}

// --caster auto on a volume prepared here decides between classifying and segmenting: one small view costs less cast
// without a field than even the hier field would take to build, so nothing is built; an orbit of larger views pays
// for the hier field (no segmentation); a long orbit pays for segmenting and EACD's field, whose views take fewer
// iterations. Each case lies far from its choice's ties whatever part of EACD's build the device's start hides (the
// head CT's 46 ms build may hide whole, which would make EACD the head CT's choice for 4 views too; the FLAIR's 333
// ms cannot), so the choices do not depend on how fast the device opens.
TEST(VolrenderCli, AutoDecidesBeforeBuildingAField) {
    const fs::path dir = test::scratchDir("volrender_cli_auto_here");
    for (const auto& [dataset, view, caster] :
         {std::tuple{"vtk_headsq_ct_64x64x93_uint16", " --size 48x40", "primitive"},
          std::tuple{"flair_mri", " --size 256x256 --views 4", "hier"},
          std::tuple{"vtk_headsq_ct_64x64x93_uint16", " --size 256x256 --views 16", "eacd"}}) {
        SCOPED_TRACE(std::string(dataset) + view);
        const test::DatasetEntry e = test::rawDataset(dataset);
        const std::string volume = q(test::datasetsDir() / e.file) + " --tf " + q(test::datasetsDir() / e.tf);
        const test::CliOutcome r = volrender(volume + view + " --elevation 20 -o " + q(dir / "v.png") + " --stats " +
                                             q(dir / "v.json"));
        ASSERT_EQ(r.status, 0) << r.err;
        const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "v.json"));
        EXPECT_EQ(stats["settings"]["caster"], caster);
        EXPECT_EQ(stats["prepareSeconds"].contains("segment"), std::string(caster) == "eacd");
        EXPECT_EQ(stats["prepareSeconds"].contains("hier"), std::string(caster) == "hier");
        const std::string why = stats["settings"]["casterChoice"];
        EXPECT_NE(why.find("cast without a field take an estimated"), std::string::npos) << why;
        EXPECT_NE(r.err.find("--caster auto chose " + std::string(caster)), std::string::npos) << r.err;
    }
}

// The shared head CT is in Hounsfield units: with CT-Bone its skull shows; a window/level ramp far above any of its
// values shows nothing; --list-presets needs no volume; the transfer-function flags are checked as volprep's.
TEST(VolrenderCli, RendersTheCraniumWithAPresetInOneCommand) {
    const fs::path dir = test::scratchDir("volrender_cli_presets");
    const test::DatasetEntry e = test::rawDataset("cranium_ct");
    const std::string volume = q(test::datasetsDir() / e.file) + " --spacing " + std::to_string(e.spacing.x) + "," +
                               std::to_string(e.spacing.y) + "," + std::to_string(e.spacing.z) +
                               " --cpu --caster primitive --size 48x48 --elevation 90 -q -o ";
    const auto visiblePixels = [&](const std::string& flags) {
        const test::CliOutcome r = volrender(volume + q(dir / "x.exr") + flags);
        EXPECT_EQ(r.status, 0) << flags << ": " << r.err;
        const Image image = readImage(dir / "x.exr");
        int visible = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) visible += image.pixel(x, y)[3] > 0.5f;
        return visible;
    };
    EXPECT_GT(visiblePixels(" --tf CT-Bone"), 48 * 48 / 5);
    EXPECT_EQ(visiblePixels(" --window 100 --level 5000"), 0);  // every value below the window

    const test::CliOutcome list = volrender("--list-presets");
    EXPECT_EQ(list.status, 0);
    EXPECT_NE(list.out.find("CT-Bone         -3024 .. 3071 HU"), std::string::npos) << list.out;
    expectRejected(volume + q(dir / "y.png") + " --tf ct-bon", "--tf ct-bon: no such file, nor a built-in preset");
    expectRejected(volume + q(dir / "y.png") + " --window -1 --level 40", "--window -1");
    expectRejected(volume + q(dir / "y.png") + " --window 400", "--window requires --level");
    expectRejected(q(preparedHead()) + " --window 400 --level 40 -o " + q(dir / "y.png"),
                   "a prepared file holds its transfer function and grid: --tf, --window, --level");
    // Nor do a prepared file's thresholds or series change: their flags are refused, not ignored.
    for (const char* flag : {" --to 0.05", " --ta 5", " --to 0.01"})
        expectRejected(q(preparedHead()) + flag + " -o " + q(dir / "y.png"),
                       "--to and --ta are for a volume to prepare");
    expectRejected(q(preparedHead()) + " --series 1.2.3 -o " + q(dir / "y.png"), "--series picks a series");
    EXPECT_FALSE(fs::exists(dir / "y.png"));
}

// The blends other than composite: the device's blocks caster renders what the CPU reference renders, where auto
// leaps by blocks.
TEST(VolrenderCli, BlendModesRenderOnTheDeviceAsOnTheCpu) {
    const fs::path dir = test::scratchDir("volrender_cli_blend");
    for (const char* blend : {"mip", "minip", "average", "iso --iso 1000"}) {
        const std::string run = q(preparedHead()) + " --size 40x36 --azimuth 30 --elevation 20 --blend " + blend;
        const test::CliOutcome device = volrender(run + " --caster blocks -o " + q(dir / "device.exr"));
        ASSERT_EQ(device.status, 0) << device.err;
        ASSERT_EQ(volrender(run + " --cpu -o " + q(dir / "cpu.exr") + " --stats " + q(dir / "s.json")).status, 0);
        const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "s.json"));
        EXPECT_EQ(stats["settings"]["caster"], "blocks") << blend;
        EXPECT_EQ(stats["settings"]["blend"], std::string(blend).substr(0, std::string(blend).find(' ')));
        const Image a = readImage(dir / "device.exr"), b = readImage(dir / "cpu.exr");
        std::size_t differ = 0;
        for (std::size_t i = 0; i < a.rgba.size(); ++i) differ += std::abs(a.rgba[i] - b.rgba[i]) > 1e-3f;
        EXPECT_LE(differ, a.rgba.size() / 50) << blend;  // float positions move a few samples to the next voxel
    }
}

// The one-command path on a terminal: a bar per preparing stage; --quiet leaves the terminal to errors.
TEST(VolrenderCli, ProgressBarsOnATerminalAndNoneWithQuiet) {
    const fs::path dir = test::scratchDir("volrender_cli_quiet");
    const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
    const std::string args = q(test::datasetsDir() / e.file) + " --tf " + q(test::datasetsDir() / e.tf) +
                             " --size 16x16 --caster eacd -o " + q(dir / "x.png");
    const test::CliOutcome shown = test::runOnTerminal(test::volrenderExecutable(), args);
    ASSERT_EQ(shown.status, 0) << shown.out;
    for (const char* stage : {"load ", "classify ", "segment ", "fields "})
        EXPECT_NE(shown.out.find(std::string(stage)), std::string::npos) << stage << " in\n" << shown.out;
    const test::CliOutcome quiet = test::runOnTerminal(test::volrenderExecutable(), args + " --quiet");
    ASSERT_EQ(quiet.status, 0) << quiet.out;
    EXPECT_EQ(quiet.out, "");
}

// Auto on a device for the blends other than composite weighs the probed iterations of blocks, each as dear as the
// calibration's ratio says, against the primitive caster's: a ratio near 0 takes blocks, a huge one primitive, both
// for a prepared file and for a volume prepared here, and the reason gives the estimates. The images agree.
TEST(VolrenderCli, AutoWeighsBlocksAgainstThePrimitiveCasterForTheOtherBlends) {
    const fs::path dir = test::scratchDir("volrender_cli_auto_blend");
    const test::DatasetEntry e = test::rawDataset("vtk_headsq_ct_64x64x93_uint16");
    const std::string here = q(test::datasetsDir() / e.file) + " --tf " + q(test::datasetsDir() / e.tf);
    const std::string view = " --size 64x64 --elevation 20 --blend mip --stats " + q(dir / "s.json") + " -o ";
    ASSERT_EQ(volrender(q(preparedHead()) + view + q(dir / "x.exr")).status, 0);
    CasterCalibration cheap = builtInCalibration(), dear = builtInCalibration();
    cheap.deviceName = dear.deviceName = nlohmann::json::parse(slurp(dir / "s.json"))["renderer"];
    cheap.blocksIterationRatio = 1e-3;
    dear.blocksIterationRatio = 1e3;
    writeCasterCalibration(dir / "cheap.json", cheap);
    writeCasterCalibration(dir / "dear.json", dear);
    for (const std::string& input : {q(preparedHead()), here})
        for (const auto& [file, caster] : {std::pair{"cheap.json", "blocks"}, std::pair{"dear.json", "primitive"}}) {
            SCOPED_TRACE(input + " " + file);
            const std::string image = std::string(caster) + (input == here ? "_here" : "_file") + ".exr";
            const test::CliOutcome r =
                volrender(input + view + q(dir / image) + " --calibration " + q(dir / file));
            ASSERT_EQ(r.status, 0) << r.err;
            const nlohmann::json stats = nlohmann::json::parse(slurp(dir / "s.json"));
            EXPECT_EQ(stats["settings"]["caster"], caster);
            const std::string why = stats["settings"]["casterChoice"];
            EXPECT_NE(why.find("cast without leaping take an estimated"), std::string::npos) << why;
            EXPECT_NE(r.err.find("--caster auto chose " + std::string(caster)), std::string::npos) << r.err;
        }
    for (const char* input : {"_here", "_file"})
        EXPECT_LT(maxAbsDifference(readImage(dir / ("blocks" + std::string(input) + ".exr")),
                                   readImage(dir / ("primitive" + std::string(input) + ".exr"))),
                  1e-4);
}

TEST(VolrenderCli, AutoTakesTheCalibrationOfItsDeviceAndSaysWhich) {
    const fs::path dir = test::scratchDir("volrender_cli_calibration"), user = dir / "config" / "volrender";
    const std::string home = "XDG_CONFIG_HOME=" + q(dir / "config");
    const std::string run = q(preparedHead()) + " -o " + q(dir / "x.png") + " --size 16x16 --caster auto --stats " +
                            q(dir / "stats.json");
    auto calibrationUsed = [&](const std::string& args) {
        const test::CliOutcome r = test::runVolrender(run + args, home);
        EXPECT_EQ(r.status, 0) << r.err;
        return nlohmann::json::parse(slurp(dir / "stats.json"));
    };
    const nlohmann::json builtIn = calibrationUsed("");
    EXPECT_EQ(builtIn["calibration"]["source"], "built-in");
    EXPECT_EQ(builtIn["calibration"]["rayNs"], builtInCalibration().rayNs);

    CasterCalibration here = builtInCalibration(), elsewhere = builtInCalibration();
    here.deviceName = builtIn["renderer"];
    here.rayNs = 99;
    elsewhere.deviceName = "another GPU";
    writeCasterCalibration(dir / "here.json", here);
    writeCasterCalibration(dir / "elsewhere.json", elsewhere);
    const nlohmann::json explicitFile = calibrationUsed(" --calibration " + q(dir / "here.json"));
    EXPECT_EQ(explicitFile["calibration"]["source"], (dir / "here.json").string());
    EXPECT_EQ(explicitFile["calibration"]["rayNs"], 99);

    fs::create_directories(user);
    writeCasterCalibration(user / "calibration.json", here);
    EXPECT_EQ(calibrationUsed("")["calibration"]["source"], (user / "calibration.json").string());
    writeCasterCalibration(user / "calibration.json", elsewhere);
    const test::CliOutcome passedOver = test::runVolrender(run, home);
    EXPECT_EQ(passedOver.status, 0) << passedOver.err;
    EXPECT_NE(passedOver.err.find("measured on 'another GPU'"), std::string::npos) << passedOver.err;
    EXPECT_NE(passedOver.err.find("using the built-in constants"), std::string::npos) << passedOver.err;

    const std::string out = q(preparedHead()) + " -o " + q(dir / "y.png") + " --caster auto --calibration ";
    expectRejected(out + q(dir / "elsewhere.json"), "elsewhere.json: measured on 'another GPU'");
    std::ofstream(dir / "malformed.json") << "{";
    expectRejected(out + q(dir / "malformed.json"), "malformed.json: not valid JSON");
    expectRejected(out + q(dir / "absent.json"), "absent.json: no such file");
    EXPECT_FALSE(fs::exists(dir / "y.png"));
}

}  // namespace
}  // namespace vr
