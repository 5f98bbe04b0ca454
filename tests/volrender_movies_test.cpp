// volrender's movies: an orbit written as one GIF or MP4 holds every view, in order, at its size and rate, each
// frame the image the same view gives as a file; wrong formats and flags are refused, and a run that does not
// finish leaves no movie.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <set>

#include "support/cli.h"
#include "support/datasets.h"
#include "support/movie_frames.h"
#include "support/render_cases.h"
#include "io/prepared_file.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using test::shellQuote;

// Three blocks of different colours placed off the axes, so that every view of an orbit differs from the next.
const fs::path& preparedBlocks() {
    const GridGeometry grid{{16, 12, 10}, {1, 1, 1.5}, {0, 0, 0}};
    static const fs::path path = test::writtenSynthetic("volrender_movies_prepared", grid, 1.0, [](const Vec3i& v) {
        if (v.x >= 2 && v.x < 6 && v.y >= 2 && v.y < 5 && v.z >= 2 && v.z < 8)
            return test::VoxelClass{0.6, {1, 0.1, 0.1}};
        if (v.x >= 10 && v.x < 14 && v.y >= 6 && v.y < 10 && v.z >= 1 && v.z < 4)
            return test::VoxelClass{0.6, {0.1, 1, 0.2}};
        if (v.x >= 4 && v.x < 12 && v.y >= 8 && v.y < 11 && v.z >= 6 && v.z < 9)
            return test::VoxelClass{0.6, {0.2, 0.3, 1}};
        return test::VoxelClass{0.0, {0, 0, 0}};
    });
    return path;
}

constexpr int kViews = 6;
std::string orbit(const fs::path& output) {
    return shellQuote(preparedBlocks()) + " -o " + shellQuote(output) + " --cpu --no-shading --nearest --caster eacd" +
           " --size 48x32 --elevation 25 --views " + std::to_string(kViews);
}

void expectRefused(const std::string& args, const std::vector<std::string>& mentions) {
    test::expectRefusal(test::runVolrender(args), "volrender", args, mentions);
}

// Each frame against the image file of its view and of the next view: the bounds must hold for its own view and
// fail for the next one, or they would not tell the frames apart.
void expectFramesAreTheViews(const test::Frames& movie, const std::vector<test::Frames>& views, double meanBound,
                             double beyond16Bound) {
    ASSERT_EQ(movie.rgb.size(), std::size_t(kViews));
    ASSERT_EQ(movie.width, 48);
    ASSERT_EQ(movie.height, 32);
    for (int i = 0; i < kViews; ++i) {
        const test::FrameDifference own = test::frameDifference(movie.rgb[i], views[i].rgb[0]);
        const test::FrameDifference next = test::frameDifference(movie.rgb[i], views[(i + 1) % kViews].rgb[0]);
        std::printf("frame %d: mean %.3f max %d levels (%.2f %% beyond 16) from its view; mean %.3f from the next\n",
                    i, own.mean, own.max, 100 * own.beyond16, next.mean);
        EXPECT_LE(own.mean, meanBound) << "frame " << i;
        EXPECT_LE(own.beyond16, beyond16Bound) << "frame " << i;
        EXPECT_GT(next.mean, meanBound) << "frame " << i;
    }
}

TEST(VolrenderMovies, GifAndMp4HoldTheViewsOfTheOrbitInOrder) {
    const fs::path dir = test::scratchDir("volrender_movies_orbit");
    ASSERT_EQ(test::runVolrender(orbit(dir / "view.png")).status, 0);
    std::vector<test::Frames> views;
    for (int i = 0; i < kViews; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "view_%03d.png", i);
        views.push_back(test::readImageBytes(dir / name));
    }

    const test::CliOutcome gif = test::runVolrender(orbit(dir / "orbit.gif"));
    ASSERT_EQ(gif.status, 0) << gif.err;
    const test::Frames gifFrames = test::readMovieFrames(dir / "orbit.gif");
    EXPECT_EQ(gifFrames.fps, 25);
    // Each frame's own palette of up to 256 colours: these views have fewer, so the frames keep them exactly
    // (measured: 0 levels). The next view is 11-15 levels away on average.
    expectFramesAreTheViews(gifFrames, views, 0.0, 0.0);

    const test::CliOutcome mp4 = test::runVolrender(orbit(dir / "orbit.mp4") + " --fps 30");
    ASSERT_EQ(mp4.status, 0) << mp4.err;
    const test::Frames mp4Frames = test::readMovieFrames(dir / "orbit.mp4");
    EXPECT_EQ(mp4Frames.fps, 30);
    // H.264 in 4:2:0 at libx264's quality 18: colour is kept at half the resolution, so the blocks' edges blur in
    // colour (measured: mean 1.9-2.2 levels, 3.4-4.6 % of the bytes beyond 16 levels).
    expectFramesAreTheViews(mp4Frames, views, 3.0, 0.08);
    EXPECT_FALSE(fs::exists(dir / "orbit_000.gif"));
    EXPECT_FALSE(fs::exists(dir / "orbit_000.mp4"));
}

// A cube whose colour runs through the RGB cube with position: its views hold far more than 256 colours, which a
// GIF frame's palette (median cut) can only approach.
TEST(VolrenderMovies, GifFramesOfManyColoursStayCloseToTheViews) {
    const GridGeometry grid{{16, 16, 16}, {1, 1, 1}, {0, 0, 0}};
    const fs::path volume = test::writtenSynthetic("volrender_movies_colours", grid, 1.0, [](const Vec3i& v) {
        return test::VoxelClass{0.3, {v.x / 15.0, v.y / 15.0, v.z / 15.0}};
    });
    const fs::path dir = test::scratchDir("volrender_movies_colours_out");
    const std::string run = shellQuote(volume) + " --cpu --no-shading --nearest --caster eacd --size 96x64 " +
                            "--azimuth 30 --elevation 25 -o ";
    ASSERT_EQ(test::runVolrender(run + shellQuote(dir / "view.png")).status, 0);
    ASSERT_EQ(test::runVolrender(run + shellQuote(dir / "view.gif")).status, 0);
    const test::Frames view = test::readImageBytes(dir / "view.png"), gif = test::readMovieFrames(dir / "view.gif");
    std::set<std::array<unsigned char, 3>> colours;
    for (std::size_t p = 0; p < view.rgb[0].size(); p += 3)
        colours.insert({view.rgb[0][p], view.rgb[0][p + 1], view.rgb[0][p + 2]});
    ASSERT_EQ(gif.rgb.size(), 1u);
    const test::FrameDifference d = test::frameDifference(gif.rgb[0], view.rgb[0]);
    std::printf("%zu colours in the view; the GIF frame: mean %.3f max %d levels (%.2f %% beyond 16)\n",
                colours.size(), d.mean, d.max, 100 * d.beyond16);
    // Measured: 2212 colours; mean 2.05 levels, the largest 32 (half the widest box of 256 over the colour cube),
    // 1.2 % of the bytes beyond 16 levels.
    EXPECT_GT(colours.size(), 1000u);
    EXPECT_LE(d.mean, 2.5);
    EXPECT_LE(d.max, 40);
    EXPECT_LE(d.beyond16, 0.02);
}

TEST(VolrenderMovies, OneViewIsAMovieOfOneFrameAndHeatMapsMayBeMoviesToo) {
    const fs::path dir = test::scratchDir("volrender_movies_one");
    const std::string one = shellQuote(preparedBlocks()) + " --cpu --no-shading --nearest --caster eacd --size 48x32";
    ASSERT_EQ(test::runVolrender(one + " -o " + shellQuote(dir / "still.gif")).status, 0);
    EXPECT_EQ(test::readMovieFrames(dir / "still.gif").rgb.size(), 1u);
    const test::CliOutcome heat =
        test::runVolrender(orbit(dir / "x.png") + " --heatmap " + shellQuote(dir / "heat.mp4"));
    ASSERT_EQ(heat.status, 0) << heat.err;
    EXPECT_EQ(test::readMovieFrames(dir / "heat.mp4").rgb.size(), std::size_t(kViews));
    EXPECT_TRUE(fs::exists(dir / "x_005.png"));
}

TEST(VolrenderMovies, WrongFormatsAndFlagsAreRefused) {
    const fs::path dir = test::scratchDir("volrender_movies_refused");
    const std::string in = shellQuote(preparedBlocks()) + " --cpu --no-shading --views 3 -o ";
    expectRefused(in + shellQuote(dir / "orbit.avi"), {"-o", "orbit.avi", "neither an image format"});
    expectRefused(in + shellQuote(dir / "orbit.gif") + " --heatmap " + shellQuote(dir / "heat.webm"),
                  {"--heatmap", "heat.webm"});
    expectRefused(in + shellQuote(dir / "orbit.mp4") + " --size 33x20", {"-o", "even width and height", "33x20"});
    expectRefused(in + shellQuote(dir / "orbit.MP4") + " --size 32x21", {"even width and height"});
    expectRefused(in + shellQuote(dir / "orbit.png") + " --fps 30", {"--fps 30", "for a movie"});
    for (const char* fps : {"0", "-5", "61"})
        expectRefused(in + shellQuote(dir / "orbit.gif") + " --fps " + fps, {"--fps"});
    EXPECT_TRUE(fs::is_empty(dir));
}

// Killed while its frames go in, or failing on the way (a heat map it cannot write, as root passes the early
// writability check on /sys): no movie and no temporary is left, and an earlier movie stays as it was.
TEST(VolrenderMovies, AnUnfinishedMovieLeavesNothing) {
    const fs::path dir = test::scratchDir("volrender_movies_unfinished");
    for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
    const fs::path out = dir / "orbit.mp4";
    test::CliOutcome failed = test::runVolrender(orbit(out) + " --heatmap /sys/heat.png");
    EXPECT_NE(failed.status, 0);
    EXPECT_TRUE(fs::is_empty(dir));

    ASSERT_EQ(test::runVolrender(orbit(out)).status, 0);
    const std::string before = test::slurp(out);
    const bool killed = test::killWhileWriting(
        test::volrenderExecutable(),
        {preparedBlocks().string(), "-o", out.string(), "--cpu", "--no-shading", "--size", "256x256", "--views",
         "400"},
        dir, ".orbit.tmp", 120);
    EXPECT_TRUE(killed) << "the render ended before its temporary movie appeared";
    EXPECT_EQ(test::slurp(out), before);
    ASSERT_EQ(test::runVolrender(orbit(out)).status, 0);  // and the next run removes the killed one's temporary
    for (const auto& entry : fs::directory_iterator(dir)) EXPECT_EQ(entry.path().filename(), "orbit.mp4");
}

// FFmpeg is volrender's movie module's (lib/volrender/volrender_movies.so above the executable's folder), not
// volrender's: a copy of volrender without its modules still renders images, and refuses a movie before it renders,
// naming the module's file and why it cannot be loaded, and writing nothing.
TEST(VolrenderMovies, WithoutTheMovieModuleImagesAreRenderedAndMoviesRefused) {
    const fs::path copy = test::copiedWithoutModules(test::volrenderExecutable(), "volrender_movies_no_module");
    const fs::path dir = copy.parent_path().parent_path(), out = dir / "out";
    fs::create_directories(out);

    const test::CliOutcome image = test::runCli(copy, orbit(out / "view.png"));
    EXPECT_EQ(image.status, 0) << image.err;
    EXPECT_TRUE(fs::exists(out / "view_005.png"));
    for (const char* movie : {"orbit.gif", "orbit.mp4"}) {
        const std::string args = orbit(out / movie);
        test::expectRefusal(test::runCli(copy, args), "volrender", args,
                            {"-o", movie, (dir / "lib/volrender/volrender_movies.so").string(),
                             "cannot load the module that writes movies", "No such file"});
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), kViews);  // the images only
}

// On a terminal a movie shows a bar over its frames and then one line; --quiet shows nothing.
TEST(VolrenderMovies, ProgressBarOverTheFrames) {
    const fs::path dir = test::scratchDir("volrender_movies_bar");
    const test::CliOutcome shown = test::runOnTerminal(test::volrenderExecutable(), orbit(dir / "orbit.gif"));
    ASSERT_EQ(shown.status, 0) << shown.out;
    EXPECT_NE(shown.out.find("frames "), std::string::npos) << shown.out;
    EXPECT_NE(shown.out.find("100%"), std::string::npos) << shown.out;
    EXPECT_NE(shown.out.find("orbit.gif: 6 frames"), std::string::npos) << shown.out;
    const test::CliOutcome quiet = test::runOnTerminal(test::volrenderExecutable(), orbit(dir / "orbit.gif") + " -q");
    ASSERT_EQ(quiet.status, 0) << quiet.out;
    EXPECT_EQ(quiet.out, "");
}

}  // namespace
}  // namespace vr
