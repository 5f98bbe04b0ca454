// The sweep's CSV rows, the Pareto front and the selection of the best setting.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/errors.h"
#include "support/datasets.h"
#include "sweep/pareto.h"
#include "sweep/selection.h"
#include "sweep/sweep_options.h"
#include "sweep/sweep_row.h"

namespace vr {
namespace {

SweepRow row(const std::string& caster, double to, double ta, double ratio, double psnrWorst, double offWorst) {
    SweepRow r;
    r.dataset = "d";
    r.caster = caster;
    r.opacityThreshold = to;
    r.angleThreshold = ta;
    r.ratioToPrimitive = ratio;
    r.error.worst.psnr = psnrWorst;
    r.error.mean.psnr = psnrWorst + 1;
    r.error.worst.percentOff8Bit = offWorst;
    return r;
}

TEST(SweepResultsCsv, RowsRoundTripThroughTheFile) {
    SweepRow r = row("eacd", 0.005, 3, 0.125, 41.5, 0.25);
    r.views = 8;
    r.width = 256;
    r.height = 128;
    r.segmentSeconds = 1.5;
    r.eacdSeconds = 0.25;
    r.regions = 123456;
    r.deviceMsMedian = 12.5;
    r.iterationsMax = 300;
    r.fieldBytes = 3LL << 32;
    r.error.mean.mse = 1e-6;
    r.error.worst.mse = 4e-6;
    r.error.mean.ssim = 0.999;
    r.error.worst.percentPerceptual = 0.5;
    SweepRow exact = row("primitive", 0, 0, 1, INFINITY, 0);
    exact.error.mean.psnr = INFINITY;

    const auto dir = test::scratchDir("sweep_csv");
    const auto csv = dir / "sweep.csv";
    appendSweepCsv(csv, {r});
    appendSweepCsv(csv, {exact});  // appends, header once
    const std::vector<SweepRow> back = readSweepCsv(csv);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(toCsvLine(back[0]), toCsvLine(r));
    EXPECT_EQ(back[0].key(), "d,0.005,3,eacd");
    EXPECT_EQ(back[0].fieldBytes, 3LL << 32);
    EXPECT_NEAR(std::sqrt(back[0].error.worst.mse), 2e-3, 1e-9);
    EXPECT_TRUE(std::isinf(back[1].error.worst.psnr));
    EXPECT_NE(toCsvLine(exact).find(",inf,inf,"), std::string::npos);
}

TEST(SweepResultsCsv, MalformedFilesAreInputErrors) {
    const auto dir = test::scratchDir("sweep_csv_bad");
    EXPECT_TRUE(readSweepCsv(dir / "missing.csv").empty());
    std::ofstream(dir / "foreign.csv") << "a,b,c\n1,2,3\n";
    EXPECT_THROW(readSweepCsv(dir / "foreign.csv"), InputError);
    std::ofstream(dir / "short.csv") << csvHeader() << "\nd,0,0,eacd,1\n";
    EXPECT_THROW(readSweepCsv(dir / "short.csv"), InputError);
    std::string line = toCsvLine(row("pc", 0, 0, 1, 50, 0));
    line.replace(line.find(",pc,") + 4, 1, "x");  // views column no longer a number
    std::ofstream(dir / "nan.csv") << csvHeader() << "\n" << line << "\n";
    EXPECT_THROW(readSweepCsv(dir / "nan.csv"), InputError);
}

TEST(SweepResultsPareto, KeepsExactlyTheNonDominatedPoints) {
    //  (1,5) (2,3) (3,4) (4,1) (2,3) (5,5)
    const std::vector<bool> f = paretoFront({{1, 5}, {2, 3}, {3, 4}, {4, 1}, {2, 3}, {5, 5}});
    EXPECT_EQ(f, (std::vector<bool>{true, true, false, true, true, false}));
    EXPECT_TRUE(paretoFront({}).empty());
}

TEST(SweepResultsSelection, BestSettingMeetsTheTargetInTheWorstView) {
    const std::vector<SweepRow> rows{
        row("primitive", 0, 0, 1, INFINITY, 0),  row("eacd", 0, 0, 0.2, INFINITY, 0),
        row("eacd", 0.01, 3, 0.1, 45, 0.5),      row("eacd", 0.1, 20, 0.05, 39.9, 0.1),  // PSNR too low
        row("eacd", 0.05, 10, 0.06, 50, 1.0),    // 1 % off: not < 1 %
        row("acd", 0.01, 3, 0.15, 60, 0)};
    const SweepRow* best = bestMeetingTarget(rows, "eacd");
    ASSERT_NE(best, nullptr);
    EXPECT_EQ(best->opacityThreshold, 0.01);
    EXPECT_NEAR(speedUp(*best), 10, 1e-12);
    EXPECT_EQ(bestMeetingTarget(rows)->caster, "eacd");
    EXPECT_EQ(bestMeetingTarget(rows, "pc"), nullptr);
    EXPECT_EQ(castersOf(rows), (std::vector<std::string>{"primitive", "eacd", "acd"}));
    // Front over (time ratio, -mean PSNR; exact plotted at 100 dB): primitive is dominated by eacd 0/0, eacd
    // 0.01/3 by eacd 0.05/10 (faster and better).
    EXPECT_EQ(psnrFront(rows), (std::vector<bool>{false, true, false, true, true, true}));
}

TEST(SweepResultsOptions, ValidatesTheGridAndNamesTheDataset) {
    SweepOptions o;
    o.input = "/data/cranium_ct_256x256x108_int16.raw.gz";
    o.transfer.tf = "tf.json";
    o.outDir = "out";
    EXPECT_NO_THROW(o.validate());
    EXPECT_EQ(o.datasetName(), "cranium_ct_256x256x108_int16");
    o.opacityThresholds = {0, -0.1};
    EXPECT_THROW(o.validate(), InputError);
    o.opacityThresholds = {0};
    o.casters = {Caster::EACD};
    EXPECT_THROW(o.validate(), InputError);
    o.casters = {Caster::Primitive};
    o.width = 8;
    EXPECT_THROW(o.validate(), InputError);
    o.width = 64;
    o.dataset = "a,b";
    EXPECT_THROW(o.validate(), InputError);
    o.dataset = "";
    o.transfer = {"", 400.0, 40.0};  // --window and --level alone: a grey ramp
    EXPECT_NO_THROW(o.validate());
    o.transfer = {};
    EXPECT_THROW(o.validate(), InputError);
}

}  // namespace
}  // namespace vr
