// The auto caster's calibration (io/caster_calibration_file.h, render/caster_choice.h): the file's round trip, its
// refusals, and the choice weighing the casters with the file's constants.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "core/distance_fields.h"
#include "core/errors.h"
#include "io/caster_calibration_file.h"
#include "render/caster_choice.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

CasterCalibration measuredElsewhere() {
    return {27, {5, 9, 11, 13}, 0.3, 0.1, "Some GPU", "1.2.3", "2026-01-02T03:04:05Z", {64e6, 0.25}};
}

TEST(RenderCasterCalibration, NamesTheCastersInTheirOrder) {
    for (Caster c : {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD})
        EXPECT_EQ(casterName(c), kCalibratedCasters[std::size_t(c)]);
}

TEST(RenderCasterCalibration, FileRoundTrip) {
    const fs::path file = test::scratchDir("calibration_round_trip") / "calibration.json";
    writeCasterCalibration(file, measuredElsewhere());
    EXPECT_EQ(readCasterCalibration(file), measuredElsewhere());
    writeCasterCalibration(file, builtInCalibration());
    EXPECT_EQ(readCasterCalibration(file), builtInCalibration());
}

TEST(RenderCasterCalibration, BuiltInIsLavapipesFit) {
    const CasterCalibration& c = builtInCalibration();
    EXPECT_EQ(c.rayNs, 44);
    EXPECT_EQ(c.iterationNs, (std::array<double, 4>{12, 14, 15, 17}));
    EXPECT_EQ(c.uploadNsPerByte, 0.14);
    EXPECT_EQ(c.tie, 0.05);
    EXPECT_EQ(c.growth, (IterationGrowth{16.8e6, 0.05}));
    EXPECT_EQ(c.blocksIterationRatio, 2.4);
    EXPECT_NE(c.deviceName.find("llvmpipe"), std::string::npos);
}

TEST(RenderCasterCalibration, AVersion1FileReadsWithoutGrowth) {
    // Written before the growth with the volume's bytes was calibrated: its constants price every volume alike.
    json j = casterCalibrationJson(measuredElsewhere());
    j["version"] = 1;
    j.erase("iterationGrowth");
    const fs::path file = test::scratchDir("calibration_version_1") / "calibration.json";
    std::ofstream(file) << j.dump();
    CasterCalibration expected = measuredElsewhere();
    expected.growth = {};
    EXPECT_EQ(readCasterCalibration(file), expected);
}

// Writes `text` as a calibration file and expects reading it to fail with a message naming the file and `says`.
void expectRefused(const std::string& name, const std::string& text, const std::string& says) {
    const fs::path file = test::scratchDir("calibration_refused") / (name + ".json");
    std::ofstream(file) << text;
    try {
        readCasterCalibration(file);
        ADD_FAILURE() << name << ": read without error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
        EXPECT_NE(message.find(says), std::string::npos) << name << ": expected '" << says << "' in " << message;
    }
}

// The good file's JSON with one change.
std::string edited(const std::function<void(json&)>& change) {
    json j = casterCalibrationJson(measuredElsewhere());
    change(j);
    return j.dump();
}

TEST(RenderCasterCalibration, AFileWithoutTheBlocksRatioLeavesItUnmeasured) {
    // Written before the blocks caster's iterations were calibrated: 0, the built-in ratio then stands.
    CasterCalibration measured = measuredElsewhere();
    measured.blocksIterationRatio = 1.4;
    json j = casterCalibrationJson(measured);
    EXPECT_EQ(j.at("blocksIterationRatio"), 1.4);
    j.erase("blocksIterationRatio");
    const fs::path file = test::scratchDir("calibration_without_blocks") / "calibration.json";
    std::ofstream(file) << j.dump();
    EXPECT_EQ(readCasterCalibration(file).blocksIterationRatio, 0);
    expectRefused("negative_blocks", edited([](json& j) { j["blocksIterationRatio"] = -1; }),
                  "blocksIterationRatio must be a finite number >= 0");
}

TEST(RenderCasterCalibration, BadFilesAreRefusedWithTheProblem) {
    expectRefused("malformed", "{\"rayNs\": 27,", "not valid JSON");
    expectRefused("nan", "{\"rayNs\": NaN}", "not valid JSON");
    expectRefused("array", "[1, 2]", "not a calibration file");
    expectRefused("other_format", edited([](json& j) { j["format"] = "something else"; }), "not a calibration file");
    expectRefused("version", edited([](json& j) { j["version"] = 3; }), "version 3 is not supported (1 or 2)");
    expectRefused("no_growth", edited([](json& j) { j.erase("iterationGrowth"); }),
                  "iterationGrowth.cachedBytes is missing");
    expectRefused("text_growth", edited([](json& j) { j["iterationGrowth"]["perDoubling"] = "0.1"; }),
                  "iterationGrowth.perDoubling must be a number");
    expectRefused("negative_growth", edited([](json& j) { j["iterationGrowth"]["perDoubling"] = -0.1; }),
                  "iterationGrowth.perDoubling must be a finite number >= 0");
    expectRefused("negative_cache", edited([](json& j) { j["iterationGrowth"]["cachedBytes"] = -1; }),
                  "iterationGrowth.cachedBytes must be a finite number >= 0");
    expectRefused("no_ray", edited([](json& j) { j.erase("rayNs"); }), "rayNs is missing");
    expectRefused("null_ray", edited([](json& j) { j["rayNs"] = nullptr; }), "rayNs must be a number");
    expectRefused("negative_ray", edited([](json& j) { j["rayNs"] = -1; }), "rayNs must be a finite number >= 0");
    expectRefused("no_eacd", edited([](json& j) { j["iterationNs"].erase("eacd"); }), "iterationNs.eacd is missing");
    expectRefused("text_pc", edited([](json& j) { j["iterationNs"]["pc"] = "9"; }), "iterationNs.pc must be a number");
    expectRefused("negative_acd", edited([](json& j) { j["iterationNs"]["acd"] = -3; }), "iterationNs.acd must be");
    expectRefused("overflow", "{\"uploadNsPerByte\": 1e999}", "not valid JSON");
    expectRefused("negative_upload", edited([](json& j) { j["uploadNsPerByte"] = -0.1; }), "uploadNsPerByte must be");
    expectRefused("tie", edited([](json& j) { j["tie"] = 1.5; }), "tie must be a fraction");
    expectRefused("no_device", edited([](json& j) { j.erase("device"); }), "device.name is missing");
    expectRefused("unnamed_device", edited([](json& j) { j["device"]["name"] = ""; }), "device.name must name");
    expectRefused("no_driver", edited([](json& j) { j["device"].erase("driverVersion"); }), "device.driverVersion");
    try {
        readCasterCalibration(test::scratchDir("calibration_refused") / "absent.json");
        ADD_FAILURE() << "an absent file was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("absent.json: no such file"), std::string::npos) << e.what();
    }
}

TEST(RenderCasterCalibration, NoFileIsWrittenThatWouldBeRefused) {
    const fs::path file = test::scratchDir("calibration_unwritten") / "calibration.json";
    CasterCalibration c = measuredElsewhere();
    c.iterationNs[1] = std::nan("");
    EXPECT_THROW(writeCasterCalibration(file, c), InputError);
    EXPECT_FALSE(fs::exists(file));
}

// A probe that finds `primitive` single samples and `pc` leaps per pixel in every direction class, with a PC field
// of `pcBytes`, viewed once along -z.
struct ProbedPc {
    std::optional<RayProbe> probe = RayProbe();
    FieldBytes bytes;
    CasterDemand demand;

    ProbedPc(double primitive, double pc, std::uint64_t pcBytes) {
        probe->stepVoxels = 0.5;
        probe->primitive.singleSamples.fill(primitive);
        probe->pc.emplace().leaps.fill(pc);
        bytes.pc = pcBytes;
        demand.octants = 1u << octantOf(0, 0, -1);
        demand.views = {1u << directionClassOf({0, 0, -1})};
    }
    Caster choose(const CasterCalibration& c) const { return chooseCaster(probe, bytes, demand, c).caster; }
};

TEST(RenderCasterCalibration, TheChoiceWeighsWithTheFilesConstants) {
    // 100 PC leaps against 120 samples: at the built-in 15 ns a leap against 11 a sample, primitive is cheaper.
    const ProbedPc scene(120, 100, 1u << 20);
    EXPECT_EQ(scene.choose(builtInCalibration()), Caster::Primitive);
    CasterCalibration slowSamples = builtInCalibration();
    slowSamples.iterationNs[std::size_t(Caster::Primitive)] = 50;
    EXPECT_EQ(scene.choose(slowSamples), Caster::PC);

    // Fewer leaps than samples, but on a device whose uploads are slow the field costs more than it saves.
    const ProbedPc big(400, 20, 1u << 30);
    EXPECT_EQ(big.choose(builtInCalibration()), Caster::PC);
    CasterCalibration slowUploads = builtInCalibration();
    slowUploads.uploadNsPerByte = 100;
    EXPECT_EQ(big.choose(slowUploads), Caster::Primitive);

    // PC 4 % cheaper: a tie that the leaner primitive wins at the built-in 5 %, not at 1 %.
    const double perSample = builtInCalibration().iterationNs[std::size_t(Caster::Primitive)];
    const double perLeap = builtInCalibration().iterationNs[std::size_t(Caster::PC)];
    const ProbedPc close(1e4, 1e4 * perSample / perLeap * 0.96, 1);
    EXPECT_EQ(close.choose(builtInCalibration()), Caster::Primitive);
    CasterCalibration narrowTie = builtInCalibration();
    narrowTie.tie = 0.01;
    EXPECT_EQ(close.choose(narrowTie), Caster::PC);
}

}  // namespace
}  // namespace vr
