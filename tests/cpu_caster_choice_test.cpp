// --caster auto's choice (render/caster_choice.h) on hand-made statistics of the form preparedStatistics writes:
// per caster and direction class, the ray probe's mean leaps and single-sample iterations per pixel at step 0.5.
#include <gtest/gtest.h>

#include <map>

#include "core/distance_fields.h"
#include "render/caster_choice.h"

namespace vr {
namespace {
using json = nlohmann::json;

// Iterations per pixel of one caster in every direction class: leaps (several samples each) and single samples.
struct Counts {
    double leaps = 0, singles = 0;
};

// Statistics of a 256^3 volume whose probe found `counts` for the casters named (the others' fields absent: no
// counts, no bytes). Field bytes as volprep stores them: PC 1, ACD 8 and EACD 24 per voxel.
json statistics(const std::map<std::string, Counts>& counts, double voxels = 256.0 * 256 * 256) {
    const std::map<std::string, double> bytesPerVoxel{{"pc", 1}, {"acd", 8}, {"eacd", 24}};
    json s{{"voxels", voxels}, {"bytes", {{"sigma", 4 * voxels}, {"colour", 12 * voxels}}}};
    json probe{{"stepVoxels", 0.5}, {"ert", 0.99}, {"raysPerSide", 32}, {"casters", json::object()}};
    for (const auto& [name, c] : counts) {
        probe["casters"][name] = {{"leaps", std::vector<double>(kDirectionClasses, c.leaps)},
                                  {"singleSamples", std::vector<double>(kDirectionClasses, c.singles)}};
        if (name != "primitive") s["bytes"][name] = bytesPerVoxel.at(name) * voxels;
    }
    s["rayProbe"] = probe;
    return s;
}

CasterDemand ortho(Vec3d direction = {0, 0, -1}) {
    CasterDemand d;
    d.octants = 1u << octantOf(direction.x, direction.y, direction.z);
    d.views = {1u << directionClassOf(direction)};
    return d;
}

TEST(CasterChoice, NoProbeGivesPrimitiveAndSaysSo) {
    EXPECT_EQ(chooseCaster(json::object(), ortho()).caster, Caster::Primitive);
    EXPECT_EQ(chooseCaster(json(nullptr), ortho()).caster, Caster::Primitive);
    // A file from before the probe: mean leaps only.
    const json old{{"voxels", 1e6}, {"leaps", {{"pcMeanRadius", 8}}}, {"bytes", {{"pc", 1e6}}}};
    const CasterChoice c = chooseCaster(old, ortho());
    EXPECT_EQ(c.caster, Caster::Primitive);
    EXPECT_NE(c.reason.find("older volprep"), std::string::npos) << c.reason;
    // Malformed counts are not trusted either, nor a probe of per-octant counts (the first probe's form).
    json bad = statistics({{"primitive", {0, 500}}, {"acd", {10, 5}}});
    bad["rayProbe"]["casters"]["primitive"]["leaps"] = json::array({1, 2});
    EXPECT_EQ(chooseCaster(bad, ortho()).caster, Caster::Primitive);
    json perOctant = statistics({{"primitive", {0, 500}}, {"acd", {10, 5}}});
    for (const char* caster : {"primitive", "acd"})
        for (const char* key : {"leaps", "singleSamples"})
            perOctant["rayProbe"]["casters"][caster][key] = std::vector<double>(kOctants, 10.0);
    EXPECT_EQ(chooseCaster(perOctant, ortho()).caster, Caster::Primitive);
}

TEST(CasterChoice, TakesTheFewestWeightedIterationsAmongTheFieldsPresent) {
    const Counts primitive{0, 500}, pc{40, 200}, acd{30, 60}, eacd{20, 40};
    EXPECT_EQ(chooseCaster(statistics({{"primitive", primitive}}), ortho()).caster, Caster::Primitive);
    EXPECT_EQ(chooseCaster(statistics({{"primitive", primitive}, {"pc", pc}}), ortho()).caster, Caster::PC);
    EXPECT_EQ(chooseCaster(statistics({{"primitive", primitive}, {"pc", pc}, {"acd", acd}}), ortho()).caster,
              Caster::ACD);
    EXPECT_EQ(chooseCaster(statistics({{"primitive", primitive}, {"pc", pc}, {"acd", acd}, {"eacd", eacd}}),
                           ortho()).caster,
              Caster::EACD);
    // A field the file lacks is no candidate, however few its counts.
    json s = statistics({{"primitive", primitive}, {"acd", acd}, {"eacd", eacd}});
    s["bytes"].erase("eacd");
    EXPECT_EQ(chooseCaster(s, ortho()).caster, Caster::ACD);
}

TEST(CasterChoice, APcIterationMustSaveMoreThanItCosts) {
    // Opaque data: every ray ends after a few samples, and a PC iteration costs more than a primitive sample.
    EXPECT_EQ(chooseCaster(statistics({{"primitive", {0, 100}}, {"pc", {0, 90}}}), ortho()).caster,
              Caster::Primitive);
    EXPECT_EQ(chooseCaster(statistics({{"primitive", {0, 100}}, {"pc", {10, 40}}}), ortho()).caster, Caster::PC);
}

TEST(CasterChoice, OnlySingleSampleIterationsFollowTheStep) {
    // ACD's iterations are leaps, EACD's are fewer but mostly single samples: at the probe's step EACD wins; at a
    // quarter of it, its single samples quadruple and ACD wins.
    const json s = statistics({{"primitive", {0, 400}}, {"acd", {60, 0}}, {"eacd", {10, 30}}});
    CasterDemand d = ortho();
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::EACD);
    d.stepVoxels = 0.125;
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::ACD);
    // At eight times the step primitive takes 50 iterations, and no caster more than it.
    d.stepVoxels = 4;
    const std::string reason = chooseCaster(s, d).reason;
    EXPECT_NE(reason.find("primitive 50.0,"), std::string::npos) << reason;
    EXPECT_NE(reason.find("acd 50.0,"), std::string::npos) << reason;
    EXPECT_NE(reason.find("eacd 13.8,"), std::string::npos) << reason;
}

TEST(CasterChoice, NearTiesGoToTheLeanerField) {
    // EACD estimated 1 % cheaper than ACD: not worth three times the bytes; a fifth cheaper: worth them. (Long rays,
    // so that the cost per ray does not count.)
    const double perAcdIteration = iterationNanoseconds(Caster::ACD) / iterationNanoseconds(Caster::EACD);
    auto eacdAt = [&](double fraction) {
        return chooseCaster(statistics({{"primitive", {0, 1e5}}, {"acd", {1000, 0}},
                                        {"eacd", {1000 * perAcdIteration * fraction, 0}}}),
                            ortho())
            .caster;
    };
    EXPECT_EQ(eacdAt(0.99), Caster::ACD);
    EXPECT_EQ(eacdAt(0.8), Caster::EACD);
}

TEST(CasterChoice, OnlyTheViewsDirectionClassesCount) {
    json s = statistics({{"primitive", {0, 500}}, {"acd", {100, 300}}, {"eacd", {100, 300}}});
    s["rayProbe"]["casters"]["acd"]["singleSamples"][octantClass(0)] = 10;   // few iterations in +x +y +z
    s["rayProbe"]["casters"]["eacd"]["singleSamples"][octantClass(7)] = 10;  // and in -x -y -z
    s["rayProbe"]["casters"]["eacd"]["singleSamples"][directionClass(0, 0, -1)] = 10;  // and along -z
    EXPECT_EQ(chooseCaster(s, ortho({1, 1, 1})).caster, Caster::ACD);
    EXPECT_EQ(chooseCaster(s, ortho({-1, -1, -1})).caster, Caster::EACD);
    EXPECT_EQ(chooseCaster(s, ortho({0, 0, -1})).caster, Caster::EACD);
    // Elsewhere they leap alike, and 400 leaping iterations cost more than 500 samples: off the axis too, though
    // the view's octant (+x +y -z) holds the axis.
    EXPECT_EQ(chooseCaster(s, ortho({1, -1, 1})).caster, Caster::Primitive);
    EXPECT_EQ(chooseCaster(s, ortho({0.1, 0, -1})).caster, Caster::Primitive);
    // A view whose rays span octants 0 and 7 (perspective) averages them: ACD and EACD 255 iterations each, a tie
    // the leaner ACD wins.
    CasterDemand both = ortho({1, 1, 1});
    both.octants = 1u | 1u << 7;
    both.views = {1u << octantClass(0) | 1u << octantClass(7)};
    EXPECT_EQ(chooseCaster(s, both).caster, Caster::ACD);
    // Views are averaged: one along -z (EACD 110) and one in +x +y +z (ACD 110, EACD 400).
    CasterDemand two = ortho({0, 0, -1});
    two.octants |= 1u;
    two.views.push_back(1u << octantClass(0));
    const std::string reason = chooseCaster(s, two).reason;
    EXPECT_NE(reason.find("acd 255.0,"), std::string::npos) << reason;
    EXPECT_NE(reason.find("eacd 255.0,"), std::string::npos) << reason;
}

TEST(CasterChoice, ATinyImageDoesNotPayForAHugeUpload) {
    const json s = statistics({{"primitive", {0, 1000}}, {"pc", {100, 200}}, {"acd", {50, 20}}, {"eacd", {30, 10}}},
                              512.0 * 512 * 512);
    CasterDemand d = ortho();
    d.views.assign(100, d.views.front());  // an orbit sharing one upload
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::EACD);
    d.pixels = 16;  // 4x4 pixels: rendering costs less than uploading any field
    d.views.resize(1);
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::Primitive);
}

TEST(CasterChoice, PerspectiveUploadsEveryOctantItsRaysHave) {
    // EACD's fewer iterations pay for one octant's bytes, not for all eight: then ACD (a third of the bytes).
    const json s = statistics({{"primitive", {0, 1000}}, {"acd", {60, 20}}, {"eacd", {40, 10}}}, 512.0 * 512 * 512);
    CasterDemand d = ortho();
    d.pixels = 1024 * 1024;
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::EACD);
    d.octants = 0xff;
    EXPECT_EQ(chooseCaster(s, d).caster, Caster::ACD);
}

TEST(CasterChoice, SaysWhy) {
    // Every candidate with its estimated iterations per pixel and relative cost.
    const CasterChoice c =
        chooseCaster(statistics({{"primitive", {0, 500}}, {"pc", {40, 200}}, {"acd", {30, 60}}, {"eacd", {20, 40}}}),
                     ortho());
    for (const char* caster : {"primitive 500.0, 1.000", "pc 240.0,", "acd 90.0,", "eacd 60.0,"})
        EXPECT_NE(c.reason.find(caster), std::string::npos) << c.reason;
}

}  // namespace
}  // namespace vr
