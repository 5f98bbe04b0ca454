// volrender's stereo pairs: --stereo writes both eyes (separate files, side by side, top and bottom, or a red-cyan
// anaglyph, each the eyes' images), the stats hold each eye's device time and the share of the right eye re-cast,
// an orbit of pairs numbers them; bad separations, focus distances, layouts and projections are refused, naming
// the flag, with nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "io/prepared_file.h"
#include "render/image.h"
#include "support/cli.h"
#include "support/datasets.h"
#include "support/render_cases.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using test::shellQuote;

// Two blocks at different depths: the pair's eyes see them shifted by different disparities.
const fs::path& preparedBlocks() {
    const GridGeometry grid{{16, 12, 16}, {1, 1, 1}, {0, 0, 0}};
    static const fs::path path = test::writtenSynthetic("volrender_stereo_prepared", grid, 1.0, [](const Vec3i& v) {
        if (v.x >= 2 && v.x < 7 && v.y >= 2 && v.y < 9 && v.z >= 11 && v.z < 14)
            return test::VoxelClass{0.8, {1, 0.2, 0.1}};
        if (v.x >= 8 && v.x < 14 && v.y >= 3 && v.y < 10 && v.z >= 1 && v.z < 4)
            return test::VoxelClass{0.8, {0.1, 0.4, 1}};
        return test::VoxelClass{0.0, {0, 0, 0}};
    });
    return path;
}

std::string pairArgs(const fs::path& output, const std::string& more) {
    return shellQuote(preparedBlocks()) + " -o " + shellQuote(output) +
           " --no-shading --nearest --caster eacd --size 40x30 --projection persp --stereo 3 " + more;
}

void expectRefused(const std::string& args, const std::vector<std::string>& mentions) {
    test::expectRefusal(test::runVolrender(args), "volrender", args, mentions);
}

void expectSameImage(const Image& a, const Image& b, const std::string& what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.height, b.height) << what;
    EXPECT_LE(maxAbsDifference(a, b), 1.0 / 255) << what;  // both 8-bit
}

TEST(VolrenderStereo, LayoutsHoldBothEyes) {
    const fs::path dir = test::scratchDir("volrender_stereo_layouts");
    const test::CliOutcome separate = test::runVolrender(pairArgs(dir / "pair.png", "--cpu"));
    ASSERT_EQ(separate.status, 0) << separate.err;
    EXPECT_FALSE(fs::exists(dir / "pair.png"));
    const Image left = readImage(dir / "pair_left.png"), right = readImage(dir / "pair_right.png");
    ASSERT_EQ(left.width, 40);
    EXPECT_GT(maxAbsDifference(left, right), 0.1);  // the eyes differ
    for (const char* layout : {"side-by-side", "top-bottom", "anaglyph"}) {
        const fs::path out = dir / (std::string(layout) + ".png");
        const test::CliOutcome r = test::runVolrender(pairArgs(out, std::string("--cpu --stereo-layout ") + layout));
        ASSERT_EQ(r.status, 0) << r.err;
        const Image both = readImage(out);
        const bool beside = std::string(layout) == "side-by-side", above = std::string(layout) == "top-bottom";
        ASSERT_EQ(both.width, beside ? 80 : 40) << layout;
        ASSERT_EQ(both.height, above ? 60 : 30) << layout;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x) {
                const float* l = left.pixel(x, y);
                const float* r = right.pixel(x, y);
                if (beside || above) {
                    EXPECT_EQ(std::vector<float>(l, l + 3), std::vector<float>(both.pixel(x, y), both.pixel(x, y) + 3));
                    const float* second = both.pixel(beside ? x + 40 : x, above ? y + 30 : y);
                    EXPECT_EQ(std::vector<float>(r, r + 3), std::vector<float>(second, second + 3));
                } else {
                    EXPECT_EQ(both.pixel(x, y)[0], l[0]);
                    EXPECT_EQ(both.pixel(x, y)[1], r[1]);
                    EXPECT_EQ(both.pixel(x, y)[2], r[2]);
                }
            }
    }
}

// On the device the right eye reuses the left's pixels; the stats say what each eye cost and how much was re-cast,
// and the pair is the CPU reference's within the reprojection's error.
TEST(VolrenderStereo, DevicePairReportsEachEye) {
    const fs::path dir = test::scratchDir("volrender_stereo_device");
    const test::CliOutcome r =
        test::runVolrender(pairArgs(dir / "pair.png", "--views 2 --stats " + shellQuote(dir / "stats.json")));
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(dir / "stats.json"));
    EXPECT_EQ(stats["settings"]["stereo"]["separation"], 3.0);
    EXPECT_EQ(stats["settings"]["stereo"]["reuse"], true);
    ASSERT_EQ(stats["views"].size(), 2u);
    for (const nlohmann::json& view : stats["views"]) {
        EXPECT_GE(view["left"]["deviceMs"].get<double>(), 0);
        EXPECT_GE(view["right"]["deviceMs"].get<double>(), view["reprojectMs"].get<double>());
        EXPECT_GT(view["recastFraction"].get<double>(), 0);
        EXPECT_LT(view["recastFraction"].get<double>(), 1);
        EXPECT_GE(view["recastInPartFraction"].get<double>(), 0);
        EXPECT_LE(view["recastInPartFraction"].get<double>(), view["recastFraction"].get<double>());
        EXPECT_GE(view["recastPieces"].get<int>(), 1);  // whole rays, or pieces on a discrete GPU
        EXPECT_LE(view["recastPieces"].get<int>(), 8);
        EXPECT_NEAR(view["deviceMs"].get<double>(),
                    view["left"]["deviceMs"].get<double>() + view["right"]["deviceMs"].get<double>(), 1e-9);
    }
    for (const char* file : {"pair_left_000.png", "pair_right_000.png", "pair_left_001.png", "pair_right_001.png"})
        EXPECT_TRUE(fs::exists(dir / file)) << file;
    const test::CliOutcome cpu = test::runVolrender(pairArgs(dir / "cpu.png", "--views 2 --cpu"));
    ASSERT_EQ(cpu.status, 0) << cpu.err;
    expectSameImage(readImage(dir / "pair_left_001.png"), readImage(dir / "cpu_left_001.png"), "left eye");
    const Image right = readImage(dir / "pair_right_001.png"), cpuRight = readImage(dir / "cpu_right_001.png");
    double mean = 0;
    for (std::size_t i = 0; i < right.rgba.size(); ++i) mean += std::abs(right.rgba[i] - cpuRight.rgba[i]);
    EXPECT_LE(mean / double(right.rgba.size()), 0.01);
    const test::CliOutcome full = test::runVolrender(pairArgs(dir / "full.png", "--stereo-reuse off --stats " +
                                                                                   shellQuote(dir / "full.json")));
    ASSERT_EQ(full.status, 0) << full.err;
    const nlohmann::json fullStats = nlohmann::json::parse(std::ifstream(dir / "full.json"));
    EXPECT_EQ(fullStats["views"][0]["recastFraction"], 1.0);
}

// Every blend pairs on the device, with its counts asked for or not (the blends but composite reproject the left
// eye's depth intervals, for which the left eye always counts its rays).
TEST(VolrenderStereo, EveryBlendPairsOnTheDevice) {
    const fs::path dir = test::scratchDir("volrender_stereo_blends");
    for (const char* blend : {"mip", "minip", "average", "iso --iso 0.5", "composite"})
        for (const bool stats : {false, true}) {
            const std::string name = std::string(blend).substr(0, 3) + (stats ? "_stats" : "");
            const std::string args = shellQuote(preparedBlocks()) + " -o " + shellQuote(dir / (name + ".png")) +
                                     " --no-shading --nearest --size 40x30 --projection persp --stereo 3 --blend " +
                                     blend + (stats ? " --stats " + shellQuote(dir / (name + ".json")) : "");
            const test::CliOutcome r = test::runVolrender(args);
            ASSERT_EQ(r.status, 0) << args << "\n" << r.err;
            EXPECT_TRUE(fs::exists(dir / (name + "_right.png"))) << args;
            if (!stats) continue;
            const nlohmann::json view = nlohmann::json::parse(std::ifstream(dir / (name + ".json")))["views"][0];
            EXPECT_GT(view["iterationsPerRay"]["mean"].get<double>(), 0) << args;
        }
}

TEST(VolrenderStereo, BadStereoFlagsAreRefused) {
    const fs::path dir = test::scratchDir("volrender_stereo_bad");
    const std::string in = shellQuote(preparedBlocks()) + " -o " + shellQuote(dir / "x.png") +
                           " --no-shading --nearest --size 16x12 ";
    const std::string persp = in + "--projection persp ";
    for (const char* s : {"0", "-0", "-2", "nan", "inf"})
        expectRefused(persp + "--stereo " + s, {"--stereo", "separation"});
    expectRefused(persp + "--stereo 5 --focus 4", {"--stereo 5", "--focus 4"});
    expectRefused(persp + "--stereo 1e6", {"--stereo", "focus distance"});  // beyond the volume centre's depth
    for (const char* f : {"0", "-3", "nan"}) expectRefused(persp + "--stereo 1 --focus " + f, {"--focus", "focus"});
    expectRefused(in + "--stereo 1", {"--stereo", "--projection persp"});
    expectRefused(persp + "--stereo 1 --stereo-layout diagonal", {"--stereo-layout", "diagonal"});
    expectRefused(persp + "--stereo 1 --stereo-reuse maybe", {"--stereo-reuse", "maybe"});
    expectRefused(persp + "--stereo 1 --cpu --stereo-reuse on", {"--stereo-reuse on", "--cpu"});
    expectRefused(persp + "--focus 10", {"--focus", "--stereo"});
    expectRefused(persp + "--stereo-layout anaglyph", {"--stereo-layout", "--stereo"});
    expectRefused(persp + "--stereo-reuse off", {"--stereo-reuse", "--stereo"});
    // An MP4 of the pair one above the other: the eyes' width of 15 stays odd.
    expectRefused(shellQuote(preparedBlocks()) + " -o " + shellQuote(dir / "x.mp4") + " --size 15x12 --projection "
                  "persp --stereo 1 --stereo-layout top-bottom", {"-o", "even"});
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) ADD_FAILURE() << "written: " << e.path();
}

}  // namespace
}  // namespace vr
