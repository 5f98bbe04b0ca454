// --caster auto's choice (render/caster_choice.h) on hand-made ray probes: per caster and direction class, the
// probe's mean leaps and single-sample iterations per pixel at step 0.5, and the bytes of the fields.
#include <gtest/gtest.h>

#include <map>

#include "core/distance_fields.h"
#include "render/caster_choice.h"

namespace vr {
namespace {

// Iterations per pixel of one caster in every direction class: leaps (several samples each) and single samples.
struct Counts {
    double leaps = 0, singles = 0;
};

// What a prepared file tells the choice.
struct Prepared {
    std::optional<RayProbe> probe;
    FieldBytes bytes;
};

// A 256^3 volume whose probe found `counts` for the casters named (the others' fields absent: no counts, no
// bytes). Field bytes as volprep stores them: PC 1, ACD 8 and EACD 24 per voxel.
Prepared probed(const std::map<std::string, Counts>& counts, double voxels = 256.0 * 256 * 256) {
    Prepared p{RayProbe(), {}};
    RayProbe& probe = *p.probe;
    probe.stepVoxels = 0.5;
    probe.ert = 0.99;
    for (const auto& [name, c] : counts) {
        ProbeCounts perClass;
        perClass.leaps.fill(c.leaps);
        perClass.singleSamples.fill(c.singles);
        if (name == "primitive") probe.primitive = perClass;
        if (name == "pc") {
            probe.pc = perClass;
            p.bytes.pc = std::uint64_t(voxels);
        }
        if (name == "acd") {
            probe.acd = perClass;
            p.bytes.acd = std::uint64_t(8 * voxels);
        }
        if (name == "eacd") {
            probe.eacd = perClass;
            p.bytes.eacd = std::uint64_t(24 * voxels);
        }
    }
    return p;
}

CasterChoice choose(const Prepared& p, const CasterDemand& d) { return chooseCaster(p.probe, p.bytes, d); }

CasterDemand ortho(Vec3d direction = {0, 0, -1}) {
    CasterDemand d;
    d.octants = 1u << octantOf(direction.x, direction.y, direction.z);
    d.views = {1u << directionClassOf(direction)};
    return d;
}

TEST(RenderCasterChoice, NoProbeGivesPrimitiveAndSaysSo) {
    // A file from before the probe (or of its older forms: io/ray_probe_json.h), whatever fields it has.
    const CasterChoice c = chooseCaster(std::nullopt, FieldBytes{1u << 24, 1u << 27, 1u << 28}, ortho());
    EXPECT_EQ(c.caster, Caster::Primitive);
    EXPECT_NE(c.reason.find("older volprep"), std::string::npos) << c.reason;
}

TEST(RenderCasterChoice, TakesTheFewestWeightedIterationsAmongTheFieldsPresent) {
    const Counts primitive{0, 500}, pc{40, 200}, acd{30, 60}, eacd{20, 40};
    EXPECT_EQ(choose(probed({{"primitive", primitive}}), ortho()).caster, Caster::Primitive);
    EXPECT_EQ(choose(probed({{"primitive", primitive}, {"pc", pc}}), ortho()).caster, Caster::PC);
    EXPECT_EQ(choose(probed({{"primitive", primitive}, {"pc", pc}, {"acd", acd}}), ortho()).caster,
              Caster::ACD);
    EXPECT_EQ(choose(probed({{"primitive", primitive}, {"pc", pc}, {"acd", acd}, {"eacd", eacd}}),
                           ortho()).caster,
              Caster::EACD);
    // A field the file lacks is no candidate, however few its counts.
    Prepared s = probed({{"primitive", primitive}, {"acd", acd}, {"eacd", eacd}});
    s.bytes.eacd = 0;
    EXPECT_EQ(choose(s, ortho()).caster, Caster::ACD);
}

TEST(RenderCasterChoice, APcIterationMustSaveMoreThanItCosts) {
    // Opaque data: every ray ends after a few samples, and a PC iteration costs more than a primitive sample.
    EXPECT_EQ(choose(probed({{"primitive", {0, 100}}, {"pc", {0, 90}}}), ortho()).caster,
              Caster::Primitive);
    EXPECT_EQ(choose(probed({{"primitive", {0, 100}}, {"pc", {10, 40}}}), ortho()).caster, Caster::PC);
}

TEST(RenderCasterChoice, OnlySingleSampleIterationsFollowTheStep) {
    // ACD's iterations are leaps, EACD's are fewer but mostly single samples: at the probe's step EACD wins; at a
    // quarter of it, its single samples quadruple and ACD wins.
    const Prepared s = probed({{"primitive", {0, 400}}, {"acd", {60, 0}}, {"eacd", {10, 30}}});
    CasterDemand d = ortho();
    EXPECT_EQ(choose(s, d).caster, Caster::EACD);
    d.stepVoxels = 0.125;
    EXPECT_EQ(choose(s, d).caster, Caster::ACD);
    // At eight times the step primitive takes 50 iterations, and no caster more than it.
    d.stepVoxels = 4;
    const std::string reason = choose(s, d).reason;
    EXPECT_NE(reason.find("primitive 50.0,"), std::string::npos) << reason;
    EXPECT_NE(reason.find("acd 50.0,"), std::string::npos) << reason;
    EXPECT_NE(reason.find("eacd 13.8,"), std::string::npos) << reason;
}

TEST(RenderCasterChoice, NearTiesGoToTheLeanerField) {
    // EACD estimated 1 % cheaper than ACD: not worth three times the bytes; a fifth cheaper: worth them. (Long rays,
    // so that the cost per ray does not count.)
    const std::array<double, 4>& ns = builtInCalibration().iterationNs;
    const double perAcdIteration = ns[std::size_t(Caster::ACD)] / ns[std::size_t(Caster::EACD)];
    auto eacdAt = [&](double fraction) {
        return choose(probed({{"primitive", {0, 1e5}}, {"acd", {1000, 0}},
                                        {"eacd", {1000 * perAcdIteration * fraction, 0}}}),
                            ortho())
            .caster;
    };
    EXPECT_EQ(eacdAt(0.99), Caster::ACD);
    EXPECT_EQ(eacdAt(0.8), Caster::EACD);
}

TEST(RenderCasterChoice, OnlyTheViewsDirectionClassesCount) {
    Prepared s = probed({{"primitive", {0, 500}}, {"acd", {100, 300}}, {"eacd", {100, 300}}});
    s.probe->acd->singleSamples[octantClass(0)] = 10;          // few iterations in +x +y +z
    s.probe->eacd->singleSamples[octantClass(7)] = 10;         // and in -x -y -z
    s.probe->eacd->singleSamples[directionClass(0, 0, -1)] = 10;  // and along -z
    EXPECT_EQ(choose(s, ortho({1, 1, 1})).caster, Caster::ACD);
    EXPECT_EQ(choose(s, ortho({-1, -1, -1})).caster, Caster::EACD);
    EXPECT_EQ(choose(s, ortho({0, 0, -1})).caster, Caster::EACD);
    // Elsewhere they leap alike, and 400 leaping iterations cost more than 500 samples: off the axis too, though
    // the view's octant (+x +y -z) holds the axis.
    EXPECT_EQ(choose(s, ortho({1, -1, 1})).caster, Caster::Primitive);
    EXPECT_EQ(choose(s, ortho({0.1, 0, -1})).caster, Caster::Primitive);
    // A view whose rays span octants 0 and 7 (perspective) averages them: ACD and EACD 255 iterations each, a tie
    // the leaner ACD wins.
    CasterDemand both = ortho({1, 1, 1});
    both.octants = 1u | 1u << 7;
    both.views = {1u << octantClass(0) | 1u << octantClass(7)};
    EXPECT_EQ(choose(s, both).caster, Caster::ACD);
    // Views are averaged: one along -z (EACD 110) and one in +x +y +z (ACD 110, EACD 400).
    CasterDemand two = ortho({0, 0, -1});
    two.octants |= 1u;
    two.views.push_back(1u << octantClass(0));
    const std::string reason = choose(s, two).reason;
    EXPECT_NE(reason.find("acd 255.0,"), std::string::npos) << reason;
    EXPECT_NE(reason.find("eacd 255.0,"), std::string::npos) << reason;
}

TEST(RenderCasterChoice, ATinyImageDoesNotPayForAHugeUpload) {
    const Prepared s = probed({{"primitive", {0, 1000}}, {"pc", {100, 200}}, {"acd", {50, 20}}, {"eacd", {30, 10}}},
                              512.0 * 512 * 512);
    CasterDemand d = ortho();
    d.views.assign(100, d.views.front());  // an orbit sharing one upload
    EXPECT_EQ(choose(s, d).caster, Caster::EACD);
    d.pixels = 16;  // 4x4 pixels: rendering costs less than uploading any field
    d.views.resize(1);
    EXPECT_EQ(choose(s, d).caster, Caster::Primitive);
}

TEST(RenderCasterChoice, PerspectiveUploadsEveryOctantItsRaysHave) {
    // EACD's fewer iterations pay for one octant's bytes, not for all eight: then ACD (a third of the bytes).
    const Prepared s = probed({{"primitive", {0, 1000}}, {"acd", {60, 20}}, {"eacd", {40, 10}}}, 512.0 * 512 * 512);
    CasterDemand d = ortho();
    d.pixels = 1024 * 1024;
    EXPECT_EQ(choose(s, d).caster, Caster::EACD);
    d.octants = 0xff;
    EXPECT_EQ(choose(s, d).caster, Caster::ACD);
}

TEST(RenderCasterChoice, SaysWhy) {
    // Every candidate with its estimated iterations per pixel and relative cost.
    const CasterChoice c =
        choose(probed({{"primitive", {0, 500}}, {"pc", {40, 200}}, {"acd", {30, 60}}, {"eacd", {20, 40}}}),
                     ortho());
    for (const char* caster : {"primitive 500.0, 1.000", "pc 240.0,", "acd 90.0,", "eacd 60.0,"})
        EXPECT_NE(c.reason.find(caster), std::string::npos) << c.reason;
}

TEST(RenderCasterChoice, AnIterationCostsMoreOnceTheScalarsOutgrowTheCaches) {
    const IterationGrowth growth{16e6, 0.25};
    EXPECT_EQ(iterationScale(growth, 0), 1);  // bytes unknown
    EXPECT_EQ(iterationScale(growth, 8e6), 1);
    EXPECT_EQ(iterationScale(growth, 16e6), 1);
    EXPECT_DOUBLE_EQ(iterationScale(growth, 64e6), 1.5);  // two doublings beyond
    EXPECT_EQ(iterationScale({}, 1e12), 1);                // no growth (a version 1 calibration)
}

// A field whose upload costs more than the iterations it saves on a volume the caches hold pays once the volume
// outgrows them and every iteration costs twice as much.
TEST(RenderCasterChoice, TheVolumesBytesPriceEveryIteration) {
    const CasterCalibration calibration{40, {10, 15, 17, 20}, 0.4, 0.05, "device", "", "", {1e6, 1}};
    Prepared s = probed({{"primitive", {0, 100}}, {"pc", {40, 0}}});
    s.bytes.pc = 6'250'000;  // 2.5 ms to upload
    CasterDemand d = ortho();
    d.pixels = 64 * 64;  // 100 x 10 - 40 x 15 ns saved per pixel: 1.6 ms at 1 x, 3.3 ms at 2 x
    for (double bytes : {0.0, 1e6}) {
        d.scalarBytes = bytes;
        const CasterChoice c = chooseCaster(s.probe, s.bytes, d, calibration);
        EXPECT_EQ(c.caster, Caster::Primitive) << bytes;
        EXPECT_EQ(c.reason.find("priced at"), std::string::npos) << c.reason;
    }
    d.scalarBytes = 2e6;
    const CasterChoice c = chooseCaster(s.probe, s.bytes, d, calibration);
    EXPECT_EQ(c.caster, Caster::PC);
    EXPECT_NE(c.reason.find("each iteration priced at 2.00 x its calibrated time: 2 MB of scalars"), std::string::npos)
        << c.reason;
}

// Before any field is built: primitive while its views cost less than building EACD's field, which no EACD render
// can win back; EACD once they cost more. The reason gives both estimates.
TEST(RenderCasterChoice, BeforeBuildingPrimitiveWinsUntilItsViewsCostMoreThanTheField) {
    const CasterCalibration calibration{40, {10, 15, 17, 20}, 0.4, 0.05, "device", "", "", {}};
    CasterDemand d = ortho();
    d.pixels = 512 * 512;
    const std::size_t voxels = 256 * 256 * 128;  // about 1 s to segment and build at 120 ns per voxel
    // One view of 100 iterations per pixel: 512^2 x (40 + 100 x 10) ns = 273 ms.
    const CasterChoice one = chooseBeforeBuilding({100, {}}, d, voxels, calibration);
    EXPECT_EQ(one.caster, Caster::Primitive);
    for (const char* part : {"1 view(s)", "273 ms", "100.0 iterations", "1007 ms"})
        EXPECT_NE(one.reason.find(part), std::string::npos) << one.reason;
    d.views.assign(4, d.views.front());  // 1090 ms of primitive frames
    EXPECT_EQ(chooseBeforeBuilding({100, {}}, d, voxels, calibration).caster, Caster::EACD);
    EXPECT_EQ(chooseBeforeBuilding({10, {}}, d, voxels, calibration).caster, Caster::Primitive);  // mostly air
}

// With the hier field probed: hier wherever its views cost less than the primitive caster's and than EACD's build
// and views; EACD over a long orbit, whose views at fewer iterations win its build back.
TEST(RenderCasterChoice, BeforeBuildingHierWinsUnlessAnOrbitIsLong) {
    const CasterCalibration calibration{40, {10, 15, 17, 20}, 0.4, 0.05, "device", "", "", {}};
    CasterDemand d = ortho();
    d.pixels = 512 * 512;
    const std::size_t voxels = 256 * 256 * 128;
    // The hier field may pay once the views cost more than its build (6 ns per voxel: 50 ms).
    EXPECT_TRUE(hierMayPay(100, d, voxels, calibration));
    EXPECT_FALSE(hierMayPay(2, d, voxels, calibration));
    // One view: 512^2 x (40 + 10 x 20) ns = 63 ms with hier, 273 ms without a field.
    const CasterChoice one = chooseBeforeBuilding({100, 10.0}, d, voxels, calibration);
    EXPECT_EQ(one.caster, Caster::Hier);
    for (const char* part : {"273 ms", "hier field, built, 63 ms (10.0 iterations", "1007 ms"})
        EXPECT_NE(one.reason.find(part), std::string::npos) << one.reason;
    // Hier leaping no better than primitive stepping: primitive.
    EXPECT_EQ(chooseBeforeBuilding({10, 10.0}, d, voxels, calibration).caster, Caster::Primitive);
    // 200 views: EACD's build is won back by its fewer iterations.
    d.views.assign(200, d.views.front());
    EXPECT_EQ(chooseBeforeBuilding({100, 10.0}, d, voxels, calibration).caster, Caster::EACD);
}

// A small volume rendered in the process that prepares it: EACD's build, beside the device's start, costs only what
// outlasts it, so EACD's fewer iterations win a single view; without the wait, hier does.
TEST(RenderCasterChoice, BeforeBuildingAFieldBuiltWhileTheDeviceStartsCostsOnlyWhatOutlastsIt) {
    const CasterCalibration calibration{40, {10, 15, 17, 20}, 0.4, 0.05, "device", "", "", {}};
    CasterDemand d = ortho();
    d.pixels = 512 * 512;
    const std::size_t voxels = 64 * 64 * 96;  // EACD: 47 ms to build at 120 ns per voxel
    // One view: hier 512^2 x (40 + 33 x 20) ns = 184 ms; EACD 0.8 x 33 iterations: 149 ms and its build.
    const ProbedIterations it{100, 33.0};
    EXPECT_EQ(chooseBeforeBuilding(it, d, voxels, calibration).caster, Caster::Hier);
    d.deviceWaitMs = 40;
    const CasterChoice c = chooseBeforeBuilding(it, d, voxels, calibration);
    EXPECT_EQ(c.caster, Caster::EACD);
    EXPECT_NE(c.reason.find("47 ms to build (40 ms of it while the device gets ready)"), std::string::npos) << c.reason;
    // A wait longer than the build leaves none of it to pay. Without a hier probe EACD's views are not priced, and
    // its whole build counts; the hier field is built to probe only where it pays without the wait.
    d.deviceWaitMs = 100;
    EXPECT_NE(chooseBeforeBuilding(it, d, voxels, calibration).reason.find("(47 ms of it"), std::string::npos);
    EXPECT_EQ(chooseBeforeBuilding({100, {}}, d, voxels, calibration).caster, Caster::EACD);  // 273 ms > 47 ms
    EXPECT_EQ(chooseBeforeBuilding({10, {}}, d, voxels, calibration).caster, Caster::Primitive);  // 37 ms < 47 ms
    d.pixels = 48 * 40;  // 0.1 ms of views against the hier field's 2.4 ms, which the wait does not excuse
    EXPECT_FALSE(hierMayPay(1, d, voxels, calibration));
}

// What a one-command render waits for: the rest of the device's start while it opens, and a pipeline either way.
TEST(RenderCasterChoice, TheDeviceWaitIsTheRestOfItsStartAndAPipeline) {
    const double pipeline = deviceWaitMs(0, true);
    EXPECT_GT(pipeline, 0);
    EXPECT_EQ(deviceWaitMs(1e6, false), pipeline);
    EXPECT_GT(deviceWaitMs(0, false), pipeline);
    EXPECT_GT(deviceWaitMs(1, false), deviceWaitMs(10, false));
}

// The same volume and views: primitive while the scalars fit the caches (its frame costs less than building even
// the hier field, so that the field is not built to probe it), hier once they outgrow them and every iteration
// costs twice as much, which hier's fewer iterations save.
TEST(RenderCasterChoice, BeforeBuildingALargeVolumeTakesHier) {
    const std::size_t voxels = 256 * 256 * 256;  // the hier field: 101 ms to build at 6 ns per voxel
    const CasterCalibration calibration{40, {10, 15, 17, 20}, 0.4, 0.05, "device", "", "", {voxels / 2.0, 0.5}};
    CasterDemand d = ortho();
    d.pixels = 512 * 512;
    const ProbedIterations it{32, 5.0};
    d.scalarBytes = voxels / 2.0;  // 1 x: primitive's frame 94 ms
    EXPECT_FALSE(hierMayPay(it.primitive, d, voxels, calibration));
    EXPECT_EQ(chooseBeforeBuilding({it.primitive, {}}, d, voxels, calibration).caster, Caster::Primitive);
    d.scalarBytes = voxels * 2.0;  // two doublings beyond: 2 x, primitive's frame 178 ms, hier's 63 ms + its build
    EXPECT_TRUE(hierMayPay(it.primitive, d, voxels, calibration));
    const CasterChoice c = chooseBeforeBuilding(it, d, voxels, calibration);
    EXPECT_EQ(c.caster, Caster::Hier);
    for (const char* part : {"178 ms", "63 ms", "priced at 2.00 x"})
        EXPECT_NE(c.reason.find(part), std::string::npos) << c.reason;
}

}  // namespace

// The blends other than composite: blocks where its iterations, each blocksIterationRatio times as dear, and the
// extrema's build cost less than the primitive caster's; the primitive caster on a tie. A calibration without the
// ratio takes the built-in one.
TEST(RenderCasterChoice, AnotherBlendLeapsByBlocksOnlyWhereItsDearerIterationsPay) {
    CasterCalibration calibration{40, {10, 15, 17, 20}, 0.4, 0.05, "device", "", "", {}, 2};
    CasterDemand d = ortho();
    d.pixels = 512 * 512;
    const std::size_t voxels = 256 * 256 * 128;  // the extrema: 25 ms at 3 ns per voxel
    // Primitive: 512^2 x (40 + 140 x 10) ns = 377 ms; blocks: 512^2 x (40 + 40 x 20) ns + 25 ms = 245 ms.
    const CasterChoice teapot = chooseBlendCaster(140, 40, d, voxels, calibration);
    EXPECT_EQ(teapot.caster, Caster::Blocks);
    for (const char* part : {"1 view(s)", "377 ms (140.0 iterations", "245 ms (40.0 iterations", "2.00 times"})
        EXPECT_NE(teapot.reason.find(part), std::string::npos) << teapot.reason;
    // Blocks halves the iterations, at twice the price: no gain, and the extrema to build.
    EXPECT_EQ(chooseBlendCaster(140, 70, d, voxels, calibration).caster, Caster::Primitive);
    // The same counts on a device where a blocks iteration costs as much as a primitive one.
    calibration.blocksIterationRatio = 1;
    EXPECT_EQ(chooseBlendCaster(140, 70, d, voxels, calibration).caster, Caster::Blocks);
    // Not measured: the built-in ratio.
    calibration.blocksIterationRatio = 0;
    const double builtIn = builtInCalibration().blocksIterationRatio;
    EXPECT_GT(builtIn, 1);
    EXPECT_NE(chooseBlendCaster(140, 70, d, voxels, calibration).reason.find(std::to_string(builtIn).substr(0, 4)),
              std::string::npos);
}

}  // namespace vr
