// The CI variant of the sweep: the small real MRI head, a 2x2 grid including (0,0) and the largest thresholds,
// 2 views of 64x64 on the Vulkan device; checks the outputs and what the figures must say.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "core/errors.h"
#include "support/datasets.h"
#include "sweep/error_plot.h"
#include "sweep/report.h"
#include "sweep/run_sweep.h"
#include "sweep/stereo_row.h"
#include "sweep/sweep_row.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

SweepOptions smokeOptions(const fs::path& out) {
    SweepOptions o;
    o.input = test::datasetsDir() / "vtk_headmr_48x62x42_uint8.raw.gz";
    o.transfer.tf = (test::datasetsDir() / "mri.tf.json").string();
    o.raw.spacing = Vec3d{4, 4, 4};
    o.opacityThresholds = {0, 0.1};
    o.angleThresholds = {0, 20};
    o.views = 2;
    o.width = o.height = 64;
    // Nearest: on this small noisy head, regions made for trilinear sampling at (0.1, 20) are mostly border voxels,
    // which leap nowhere: no error to see growing.
    o.trilinear = false;
    o.outDir = out;
    return o;
}

TEST(SweepSmoke, HeadMrTwoByTwoGrid) {
    const fs::path out = test::scratchDir("sweep_smoke");
    const SweepOptions o = smokeOptions(out);
    ASSERT_EQ(runSweep(o), 4);
    const fs::path report = writeReport(out);

    const std::vector<SweepRow> rows = readSweepCsv(out / "sweep.csv");
    ASSERT_EQ(rows.size(), 16u);  // 4 settings x 4 casters
    EXPECT_TRUE(fs::exists(report));
    EXPECT_GT(fs::file_size(report), 1000u);
    EXPECT_TRUE(fs::exists(out / "strips" / (o.datasetName() + ".png")));
    if (gnuplotAvailable())
        EXPECT_TRUE(fs::exists(out / "plots" / (o.datasetName() + ".png")));
    else
        ADD_FAILURE() << "gnuplot is not installed (bash scripts/install-deps.sh gnuplot-nox): no plot checked";

    // At thresholds 0 every caster gives the reference image (up to float rounding).
    std::map<std::string, std::map<std::pair<double, double>, double>> rmse;  // caster -> setting -> RMSE
    for (const SweepRow& r : rows) {
        EXPECT_EQ(r.views, 2);
        EXPECT_GT(r.deviceMsMedian, 0);
        EXPECT_GE(r.iterationsMax, r.iterationsMean);
        EXPECT_GT(r.ratioToPrimitive, 0);
        if (r.opacityThreshold == 0 && r.angleThreshold == 0) {
            EXPECT_TRUE(std::isinf(r.error.worst.psnr) || r.error.worst.psnr > 90) << r.key();
        }
        if (r.caster == "primitive") {
            EXPECT_EQ(r.error.mean.mse, 0) << "the primitive caster does not depend on the thresholds";
            EXPECT_EQ(r.ratioToPrimitive, 1);
        }
        rmse[r.caster][{r.opacityThreshold, r.angleThreshold}] = std::sqrt(r.error.mean.mse);
    }
    // The largest thresholds give the largest error, and some caster's error there is not zero.
    bool someError = false;
    for (const auto& [caster, bySetting] : rmse) {
        const double largest = bySetting.at({0.1, 20});
        for (const auto& [setting, e] : bySetting) EXPECT_LE(e, largest) << caster;
        someError = someError || largest > 0;
    }
    EXPECT_TRUE(someError);

    // The speed-up target's line splits the best EACD speed-up into the iteration ratio and the cost of an iteration
    // (at thresholds 0, EACD meets the quality target, so some setting does).
    std::ifstream in(report);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t target = text.find("**Speed-up target");
    ASSERT_NE(target, std::string::npos);
    const std::string line = text.substr(target, text.find('\n', target) - target);
    EXPECT_NE(line.find("fewer iterations per ray than the primitive caster"), std::string::npos) << line;
    EXPECT_NE(line.find("primitive samples"), std::string::npos) << line;

    // The dataset's stereo row: the pair against one eye, the reused right eye against its full render, in the
    // dataset's section and the table at a glance.
    const std::vector<StereoRow> stereo = readStereoCsv(out / "stereo.csv");
    ASSERT_EQ(stereo.size(), 1u);
    const StereoRow& pair = stereo.front();
    EXPECT_EQ(pair.dataset, o.datasetName());
    EXPECT_EQ(pair.views, 2);
    EXPECT_GT(pair.oneEyeMs, 0);
    EXPECT_GT(pair.pairMs, pair.reprojectMs);
    EXPECT_GT(pair.recastPercent, 0);
    EXPECT_LE(pair.recastPercent, 100);
    EXPECT_GT(pair.error.worst.ssim, 0.9);
    EXPECT_TRUE(fs::exists(imagesDir(out, o.datasetName()) / "stereo_right.png"));
    EXPECT_NE(text.find("## Stereo pairs at a glance"), std::string::npos);
    EXPECT_NE(text.find("| " + o.datasetName() + " | primitive |"), std::string::npos);
    if (gnuplotAvailable()) {
        std::ifstream data(out / "plots" / (o.datasetName() + ".dat"));
        const std::string points((std::istreambuf_iterator<char>(data)), std::istreambuf_iterator<char>());
        EXPECT_NE(points.find("# stereo pair"), std::string::npos);
    }
}

TEST(SweepSmoke, ResumeSkipsFinishedSettingsAndReRunsAreRefused) {
    const fs::path out = test::scratchDir("sweep_resume");
    SweepOptions o = smokeOptions(out);
    o.opacityThresholds = {0};
    o.angleThresholds = {0};
    o.casters = {Caster::Primitive, Caster::EACD};
    o.views = 1;
    ASSERT_EQ(runSweep(o), 1);
    o.resume = true;
    EXPECT_EQ(runSweep(o), 0);
    o.angleThresholds = {0, 3};
    EXPECT_EQ(runSweep(o), 1);
    EXPECT_EQ(readSweepCsv(out / "sweep.csv").size(), 4u);
    EXPECT_EQ(readStereoCsv(out / "stereo.csv").size(), 1u);  // measured once per dataset
    o.resume = false;
    EXPECT_THROW(runSweep(o), InputError);
    // Rows of the dataset rendered otherwise are not joined, with or without --resume: the report would compare
    // them as alike.
    const auto refusal = [&](SweepOptions other) {
        try {
            runSweep(other);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    for (bool resume : {true, false}) {
        SweepOptions other = o;
        other.resume = resume;
        other.angleThresholds = {10};  // a setting not run yet
        other.width = 32;
        EXPECT_NE(refusal(other).find("rendered at 64x64, 1 views"), std::string::npos) << refusal(other);
        other = o, other.resume = resume, other.angleThresholds = {10};
        other.stepVoxels = 0.25;
        EXPECT_NE(refusal(other).find("step=0.25"), std::string::npos) << refusal(other);
        other.stepVoxels = o.stepVoxels, other.trilinear = true;
        EXPECT_NE(refusal(other).find("trilinear"), std::string::npos) << refusal(other);
        other.trilinear = false, other.elevations = {0, 30};
        EXPECT_NE(refusal(other).find("elevations=0;30"), std::string::npos) << refusal(other);
        other.elevations = {0}, other.transfer.window = 100, other.transfer.level = 50;
        EXPECT_NE(refusal(other).find("window=100 level=50"), std::string::npos) << refusal(other);
    }
    EXPECT_EQ(readSweepCsv(out / "sweep.csv").size(), 4u);
    // Under another name they are rows of their own.
    o.angleThresholds = {0};
    o.width = 32;
    o.dataset = "headmr_small";
    EXPECT_EQ(runSweep(o), 1);
    const std::vector<SweepRow> rows = readSweepCsv(out / "sweep.csv");
    ASSERT_EQ(rows.size(), 6u);
    EXPECT_EQ(rows.back().render, "tf=mri.tf.json nearest shaded step=0.5 elevations=0");
    // The stereo row is measured first: a sweep stopped before its settings' rows leaves it alone, and it is not
    // joined either.
    fs::remove(out / "sweep.csv");
    o.width = 48;
    EXPECT_NE(refusal(o).find("stereo.csv"), std::string::npos) << refusal(o);
    EXPECT_EQ(readStereoCsv(out / "stereo.csv").back().render, rows.back().render);
}

TEST(SweepSmoke, BadInputNamesTheProblem) {
    const fs::path out = test::scratchDir("sweep_bad");
    SweepOptions o = smokeOptions(out);
    o.input = out / "missing_16x16x16_uint8.raw";
    try {
        runSweep(o);
        FAIL() << "no error for a missing input";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing_16x16x16_uint8.raw"), std::string::npos) << e.what();
    }
    EXPECT_THROW(writeReport(out / "nothing"), InputError);
}

}  // namespace
}  // namespace vr
