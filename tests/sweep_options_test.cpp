// volsweep's options, checked before anything is loaded or written: each bad one is refused with a message that
// names its flag (or what is missing).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "core/errors.h"
#include "support/datasets.h"
#include "sweep/sweep_options.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

SweepOptions goodOptions() {
    SweepOptions o;
    o.input = "head_16x16x16_uint8.raw";
    o.transfer.tf = "CT-Bone";
    o.outDir = "out";
    return o;
}

// The options with `change` applied are refused, and the message holds `named`.
void expectRefused(const std::function<void(SweepOptions&)>& change, const std::string& named) {
    SweepOptions o = goodOptions();
    change(o);
    try {
        o.validate();
        ADD_FAILURE() << "accepted; expected a refusal naming " << named;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
}

TEST(SweepOptions, GoodOptionsPass) {
    EXPECT_NO_THROW(goodOptions().validate());
    SweepOptions o = goodOptions();
    o.transfer = TransferChoice{};
    o.transfer.window = 400;
    o.transfer.level = 40;
    EXPECT_NO_THROW(o.validate());
}

TEST(SweepOptions, MissingInputsAreNamed) {
    expectRefused([](SweepOptions& o) { o.input.clear(); }, "no input volume");
    expectRefused([](SweepOptions& o) { o.transfer = TransferChoice{}; }, "--tf");
    expectRefused([](SweepOptions& o) { o.outDir.clear(); }, "-o OUTDIR");
    // A file where the output folder should be (the sweep failed after loading, on "cannot create directories").
    const fs::path file = fs::temp_directory_path() / "sweep_options_out_is_a_file";
    std::ofstream(file) << "x";
    expectRefused([&](SweepOptions& o) { o.outDir = file; }, "a file, not a folder");
    fs::remove(file);
}

TEST(SweepOptions, BadThresholdGridsAreRefused) {
    for (const double bad : {-0.01, double(NAN), double(INFINITY)}) {
        expectRefused([&](SweepOptions& o) { o.opacityThresholds = {0, bad}; }, "--to");
        expectRefused([&](SweepOptions& o) { o.angleThresholds = {bad}; }, "--ta");
    }
    // Unshaded regions have no normals: an angle above 0 would repeat the same setting.
    expectRefused([](SweepOptions& o) { o.shading = false, o.angleThresholds = {0, 3}; }, "--no-shading");
    SweepOptions unshaded = goodOptions();
    unshaded.shading = false;
    unshaded.angleThresholds = {0};
    EXPECT_NO_THROW(unshaded.validate());
    expectRefused([](SweepOptions& o) { o.opacityThresholds.clear(); }, "--to");
    expectRefused([](SweepOptions& o) { o.angleThresholds.clear(); }, "--ta");
}

TEST(SweepOptions, CastersNeedThePrimitiveReference) {
    expectRefused([](SweepOptions& o) { o.casters = {Caster::EACD, Caster::PC}; }, "--casters");
}

TEST(SweepOptions, OutOfRangeCountsAndSizesAreRefused) {
    for (const int bad : {0, 17, -1}) expectRefused([&](SweepOptions& o) { o.downsample = bad; }, "--downsample");
    for (const int bad : {0, 361}) expectRefused([&](SweepOptions& o) { o.views = bad; }, "--views");
    expectRefused([](SweepOptions& o) { o.elevations.clear(); }, "--elevations");
    expectRefused([](SweepOptions& o) { o.elevations = {20, NAN}; }, "--elevations");
    // SSIM's window is 11 pixels: smaller images cannot be compared.
    for (const std::pair<int, int>& size : {std::pair{10, 64}, {64, 10}, {8193, 64}, {64, 8193}, {0, 0}})
        expectRefused([&](SweepOptions& o) { o.width = size.first, o.height = size.second; }, "--size");
    for (const double bad : {0.0, -0.5, double(NAN), double(INFINITY)})
        expectRefused([&](SweepOptions& o) { o.stepVoxels = bad; }, "--step");
}

TEST(SweepOptions, PeersFolderNeedsItsResults) {
    const fs::path dir = test::scratchDir("sweep_options_peers");
    expectRefused([&](SweepOptions& o) { o.peersDir = dir; }, "--peers");
    std::ofstream(dir / "peers.json") << R"({"peers": []})";
    SweepOptions o = goodOptions();
    o.peersDir = dir;
    EXPECT_NO_THROW(o.validate());
}

TEST(SweepOptions, DatasetNamesFitTheCsv) {
    expectRefused([](SweepOptions& o) { o.dataset = "a,b"; }, "--name");
    expectRefused([](SweepOptions& o) { o.dataset = "say \"hi\""; }, "--name");
    SweepOptions o = goodOptions();
    EXPECT_EQ(o.datasetName(), "head_16x16x16_uint8");
    o.input = "ct.nii.gz";
    o.jitter = true;
    EXPECT_EQ(o.datasetName(), "ct+jitter");
}

}  // namespace
}  // namespace vr
