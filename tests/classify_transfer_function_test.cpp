// Transfer functions: ParaView preset parsing, midpoint/sharpness and colour semantics, sampling, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/errors.h"
#include "preprocess/classify/transfer_function.h"
#include "support/load_dataset.h"

namespace vr {
namespace {

TransferFunction ramp(double x0, double y0, double x1, double y1, double mid = 0.5, double sharp = 0.0) {
    TransferFunction tf;
    tf.opacity = {{x0, y0, mid, sharp}, {x1, y1}};
    return tf;
}

// ParaView's (vtkPiecewiseFunction's) segment shape written out from its documentation, for hand values.
double paraviewSegment(double s, double y0, double y1, double mid, double sharp) {
    s = s < mid ? 0.5 * s / mid : 0.5 + 0.5 * (s - mid) / (1 - mid);
    if (sharp > 0.99) return s < 0.5 ? y0 : y1;
    if (sharp < 0.01) return (1 - s) * y0 + s * y1;
    if (s < 0.5) s = 0.5 * std::pow(s * 2, 1 + 10 * sharp);
    else if (s > 0.5) s = 1 - 0.5 * std::pow((1 - s) * 2, 1 + 10 * sharp);
    const double ss = s * s, sss = ss * s;
    const double h1 = 2 * sss - 3 * ss + 1, h2 = -2 * sss + 3 * ss, h3 = sss - 2 * ss + s, h4 = sss - ss;
    const double t = (1 - sharp) * (y1 - y0);
    return std::clamp(h1 * y0 + h2 * y1 + h3 * t + h4 * t, std::min(y0, y1), std::max(y0, y1));
}

std::string errorOf(const std::string& json, const std::string& source = "bad.tf.json") {
    try {
        parseTransferFunction(json, source);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ClassifyTransferFunction, ParsesEveryShippedPreset) {
    int presets = 0;
    for (const auto& entry : std::filesystem::directory_iterator(test::datasetsDir())) {
        const std::string file = entry.path().filename().string();
        if (!file.ends_with(".tf.json")) continue;
        SCOPED_TRACE(file);
        const TransferFunction tf = loadTransferFunction(entry.path());
        EXPECT_FALSE(tf.name.empty());
        EXPECT_GE(tf.opacity.size(), 2u);
        EXPECT_EQ(tf.colour.size(), 4u);
        EXPECT_EQ(tf.colourSpace, "RGB");
        EXPECT_FALSE(tf.json.empty());
        // At its points the function takes the points' values; beyond them, the end values.
        for (const auto& p : tf.opacity) EXPECT_NEAR(tf.opacityAt(p.x), p.opacity, 1e-12);
        EXPECT_NEAR(tf.opacityAt(tf.opacity.front().x - 1000), tf.opacity.front().opacity, 1e-12);
        EXPECT_NEAR(tf.opacityAt(tf.opacity.back().x + 1000), tf.opacity.back().opacity, 1e-12);
        for (const auto& c : tf.colour) {
            const auto rgb = tf.colourAt(c.x);
            EXPECT_NEAR(rgb[0], c.r, 1e-9);
            EXPECT_NEAR(rgb[1], c.g, 1e-9);
            EXPECT_NEAR(rgb[2], c.b, 1e-9);
        }
        ++presets;
    }
    EXPECT_GE(presets, 6);

    const TransferFunction cranium = test::datasetTransferFunction("cranium_ct.tf.json");
    ASSERT_EQ(cranium.opacity.size(), 7u);
    EXPECT_EQ(cranium.name, "ct-head");
    EXPECT_DOUBLE_EQ(cranium.opacity[4].x, 300);
    EXPECT_DOUBLE_EQ(cranium.opacity[4].opacity, 0.5);
    EXPECT_DOUBLE_EQ(cranium.opacity[4].midpoint, 0.5);
    EXPECT_DOUBLE_EQ(cranium.opacity[4].sharpness, 0.0);
    EXPECT_DOUBLE_EQ(cranium.colour[1].x, -100);
    EXPECT_DOUBLE_EQ(cranium.colour[1].g, 0.6);
    // Between points, linear: halfway from (100, 0.03) to (300, 0.5).
    EXPECT_NEAR(cranium.opacityAt(200), 0.265, 1e-12);
}

TEST(ClassifyTransferFunction, AcceptsOneObjectAsWellAsAList) {
    const std::string preset = R"({"Name": "one", "Points": [0, 0, 0.5, 0, 10, 1, 0.5, 0]})";
    EXPECT_EQ(parseTransferFunction(preset, "one.json").name, "one");
    EXPECT_EQ(parseTransferFunction("[" + preset + ", {\"Points\": []}]", "list.json").name, "one");
    const TransferFunction tf = parseTransferFunction(preset, "one.json");
    EXPECT_TRUE(tf.colour.empty());
    EXPECT_EQ(tf.colourAt(5), (std::array<double, 3>{1, 1, 1}));
}

TEST(ClassifyTransferFunction, LinearSegmentsAndClamping) {
    const TransferFunction tf = ramp(0, 0.2, 100, 1.0);
    EXPECT_NEAR(tf.opacityAt(0), 0.2, 1e-12);
    EXPECT_NEAR(tf.opacityAt(25), 0.4, 1e-12);
    EXPECT_NEAR(tf.opacityAt(50), 0.6, 1e-12);
    EXPECT_NEAR(tf.opacityAt(100), 1.0, 1e-12);
    EXPECT_NEAR(tf.opacityAt(-50), 0.2, 1e-12);
    EXPECT_NEAR(tf.opacityAt(1e9), 1.0, 1e-12);
}

TEST(ClassifyTransferFunction, MidpointAndSharpnessFollowParaView) {
    // Midpoint 0.25: the halfway value is reached a quarter of the way along the segment.
    const TransferFunction early = ramp(0, 0, 100, 1, 0.25, 0.0);
    EXPECT_NEAR(early.opacityAt(25), 0.5, 1e-12);
    EXPECT_NEAR(early.opacityAt(12.5), 0.25, 1e-12);
    EXPECT_NEAR(early.opacityAt(62.5), 0.75, 1e-12);
    // Sharpness 1: a step at the midpoint.
    const TransferFunction step = ramp(0, 0.1, 100, 0.9, 0.5, 1.0);
    EXPECT_NEAR(step.opacityAt(49), 0.1, 1e-12);
    EXPECT_NEAR(step.opacityAt(51), 0.9, 1e-12);
    // In between: the Hermite curve; the midpoint and sharpness of the segment's first point apply.
    for (double mid : {0.3, 0.5, 0.7})
        for (double sharp : {0.2, 0.5, 0.8}) {
            const TransferFunction tf = ramp(10, 0.1, 110, 0.7, mid, sharp);
            for (double x = 10; x <= 110; x += 7.5)
                EXPECT_NEAR(tf.opacityAt(x), paraviewSegment((x - 10) / 100, 0.1, 0.7, mid, sharp), 1e-9)
                    << "mid " << mid << " sharp " << sharp << " x " << x;
        }
}

TEST(ClassifyTransferFunction, ColourIsLinearInRgbAndClamped) {
    TransferFunction tf = ramp(0, 0, 1, 1);
    tf.colour = {{0, 0, 0.5, 1}, {10, 1, 0.5, 0}};
    const auto mid = tf.colourAt(2.5);
    EXPECT_NEAR(mid[0], 0.25, 1e-9);
    EXPECT_NEAR(mid[1], 0.5, 1e-9);
    EXPECT_NEAR(mid[2], 0.75, 1e-9);
    EXPECT_NEAR(tf.colourAt(-5)[2], 1.0, 1e-9);
    EXPECT_NEAR(tf.colourAt(50)[0], 1.0, 1e-9);
}

TEST(ClassifyTransferFunction, SampledTableIsExactAtSamplesAndInterpolatesBetween) {
    TransferFunction tf = test::datasetTransferFunction("cranium_ct.tf.json");
    const SampledTransferFunction exact = sampleTransferFunction(tf, -1024, 2986, 4011);  // one per integer
    for (int f = -1024; f <= 2986; f += 7) {
        EXPECT_NEAR(exact.opacityAt(f), tf.opacityAt(f), 1e-12) << f;
        const auto rgb = tf.colourAt(f);
        const auto sampled = exact.colourAt(f);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sampled[c], rgb[c], 1e-6);
    }
    EXPECT_NEAR(exact.opacityAt(-5000), 0.0, 1e-12);
    EXPECT_NEAR(exact.opacityAt(5000), 0.9, 1e-12);
    EXPECT_NEAR(exact.opacityAt(std::nan("")), 0.0, 1e-12);
    // Within a linear segment, interpolating the table is exact.
    EXPECT_NEAR(exact.opacityAt(200.5), tf.opacityAt(200.5), 1e-12);
    const SampledTransferFunction coarse = sampleTransferFunction(tf, -1024, 2986, 65536);
    for (double f = -1024; f <= 2986; f += 3.7) EXPECT_NEAR(coarse.opacityAt(f), tf.opacityAt(f), 2e-5) << f;
}

TEST(ClassifyTransferFunction, BadInputNamesTheFileAndTheProblem) {
    const auto expectError = [](const std::string& json, const std::string& problem) {
        const std::string message = errorOf(json);
        EXPECT_NE(message.find("bad.tf.json"), std::string::npos) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << "expected '" << problem << "' in: " << message;
    };
    expectError(R"([{"Points": [0, 0, 0.5, 0,)", "malformed JSON");
    expectError(R"({"Points": [0, NaN, 0.5, 0]})", "malformed JSON");
    expectError(R"({"Points": [0, 1e999, 0.5, 0]})", "malformed JSON");
    expectError("\xFF\xCC", "last read: '\\xFF'");  // a binary file's bytes quoted escaped
    expectError(R"({"RGBPoints": [0, 0, 0, 0]})", "no \"Points\"");
    expectError(R"([])", "empty");
    expectError(R"(42)", "expected a ParaView preset");
    expectError(R"({"Points": {"x": 1}})", "not a list");
    expectError(R"({"Points": [0, 0, 0.5, 0, 1, 1, 0.5]})", "not a multiple of 4");
    expectError(R"({"Points": [0, 0, 0.5, 0], "RGBPoints": [0, 1, 1]})", "not a multiple of 4");
    expectError(R"({"Points": [0, "NaN", 0.5, 0]})", "\"Points\"[1] is not a number");
    expectError(R"({"Points": [0, 0, 0.5, 0], "RGBPoints": [0, 1, null, 1]})", "\"RGBPoints\"[2] is not a number");
    expectError(R"({"Points": []})", "no opacity points");
    expectError(R"({"Points": [10, 0, 0.5, 0, 5, 1, 0.5, 0]})", "unsorted");
    expectError(R"({"Points": [10, 0, 0.5, 0, 10, 1, 0.5, 0]})", "unsorted");
    expectError(R"({"Points": [0, 0, 0.5, 0], "RGBPoints": [5, 1, 1, 1, 1, 0, 0, 0]})", "unsorted");
    expectError(R"({"Points": [0, 1.5, 0.5, 0]})", "opacity outside [0,1]");
    expectError(R"({"Points": [0, -0.1, 0.5, 0]})", "opacity outside [0,1]");
    expectError(R"({"Points": [0, 0.5, 1.5, 0]})", "midpoint or sharpness");
    expectError(R"({"Points": [0, 0, 0.5, 0], "RGBPoints": [0, 1, 1.2, 1]})", "colour outside [0,1]");
    expectError(R"({"Points": [0, 0, 0.5, 0], "ColorSpace": "CMYK"})", "unsupported ColorSpace");
    expectError(R"({"Points": [0, 0, 0.5, 0], "ColorSpace": 3})", "not a string");

    TransferFunction tf = ramp(0, 0, 1, 1);
    tf.opacity[1].opacity = std::nan("");
    EXPECT_THROW(tf.validate("programmatic"), InputError);
    try {
        tf.validate("programmatic");
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not a finite number"), std::string::npos) << e.what();
    }
}

TEST(ClassifyTransferFunction, MissingFileIsAnInputError) {
    const auto path = test::scratchDir("classify_tf") / "absent.tf.json";
    try {
        loadTransferFunction(path);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("absent.tf.json"), std::string::npos);
    }
    const auto bad = test::scratchDir("classify_tf_bad") / "bad.tf.json";
    std::ofstream(bad) << R"({"Points": [0, 0, 0.5]})";
    try {
        loadTransferFunction(bad);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(bad.string() + ": \"Points\" has 3 numbers"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace vr
