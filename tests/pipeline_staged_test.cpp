// Staged preparation: after any sequence of option changes its result equals a fresh prepareVolume, and a change
// re-runs only the stages that depend on it (a threshold change: segmentation and fields; a TF change:
// classification too; loading never).
#include <gtest/gtest.h>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "preprocess/segment/segment.h"
#include "support/datasets.h"

namespace vr {
namespace {

const char* kFile = "vtk_headsq_ct_64x64x93_uint16.raw.gz";

PrepareOptions headOptions() {
    PrepareOptions o;
    o.raw.spacing = Vec3d{3.2, 3.2, 1.5};  // MANIFEST.tsv
    o.classify.transferFunction = loadTransferFunction(test::datasetsDir() / "vtk_headsq_ct.tf.json");
    o.segmentation = {0.05, 20, true, false};
    return o;
}

std::vector<std::string> names(const std::vector<StageTime>& stages) {
    std::vector<std::string> n;
    for (const StageTime& t : stages) n.push_back(t.stage);
    return n;
}

// The statistics without the timings (which differ from run to run).
nlohmann::json untimed(nlohmann::json statistics) {
    statistics.erase("seconds");
    statistics.erase("cpuSeconds");
    return statistics;
}

// Everything prepareVolume produces, compared with the staged result.
void expectSameAsFresh(const StagedPreparation& staged, const PreparedVolume& p, const PrepareOptions& options) {
    const PrepareResult fresh = prepareVolume(test::datasetsDir() / kFile, options);
    const PreparedVolume& f = fresh.prepared;
    EXPECT_EQ(p.classified.grid, f.classified.grid);
    EXPECT_EQ(p.classified.referenceStep, f.classified.referenceStep);
    EXPECT_EQ(p.classified.sigma, f.classified.sigma);
    EXPECT_EQ(p.classified.colour, f.classified.colour);
    EXPECT_EQ(p.classified.normal, f.classified.normal);
    EXPECT_EQ(p.regions.dims, f.regions.dims);
    EXPECT_EQ(p.regions.count, f.regions.count);
    EXPECT_EQ(p.regions.label, f.regions.label);
    EXPECT_EQ(p.fields.dims, f.fields.dims);
    EXPECT_EQ(p.fields.pc, f.fields.pc);
    EXPECT_EQ(p.fields.acd, f.fields.acd);
    EXPECT_EQ(p.fields.eacd, f.fields.eacd);
    EXPECT_EQ(p.meta.source, f.meta.source);
    EXPECT_EQ(p.meta.classification, f.meta.classification);
    EXPECT_EQ(p.meta.segmentation.opacityThreshold, f.meta.segmentation.opacityThreshold);
    EXPECT_EQ(p.meta.segmentation.angleThresholdDeg, f.meta.segmentation.angleThresholdDeg);
    EXPECT_EQ(p.meta.segmentation.useNormals, f.meta.segmentation.useNormals);
    EXPECT_EQ(p.meta.segmentation.trilinear, f.meta.segmentation.trilinear);
    EXPECT_EQ(p.meta.distanceCap, f.meta.distanceCap);
    EXPECT_EQ(untimed(staged.statistics()), untimed(f.meta.statistics));
}

TEST(StagedPreparation, EachChangeReRunsOnlyTheStagesAfterIt) {
    StagedPreparation staged(test::datasetsDir() / kFile);
    PrepareOptions o = headOptions();
    const PreparedVolume& p = staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()),
              (std::vector<std::string>{"load", "classify", "segment", "acd", "pc", "eacd"}));
    expectSameAsFresh(staged, p, o);

    // The same options again: nothing runs.
    EXPECT_EQ(&staged.prepare(o), &p);
    EXPECT_TRUE(staged.lastStages().empty());

    // A threshold change: segmentation and the fields only.
    o.segmentation.opacityThreshold = 0.2;
    o.segmentation.trilinear = true;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment", "acd", "pc", "eacd"}));
    expectSameAsFresh(staged, p, o);

    // Other fields only: the fields only.
    o.fields = kFieldPC;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"pc"}));
    EXPECT_FALSE(p.fields.hasACD());
    expectSameAsFresh(staged, p, o);

    // A TF change: classification, segmentation and the fields; no loading.
    o.classify.transferFunction->opacity.back().opacity = 0.3;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "pc"}));
    expectSameAsFresh(staged, p, o);

    // Only the TF's text (not what it says) changed: no stage runs, the metadata follows.
    o.classify.transferFunction->json += " ";
    staged.prepare(o);
    EXPECT_TRUE(staged.lastStages().empty());
    EXPECT_EQ(p.meta.classification, o.classify.transferFunction->json);

    EXPECT_EQ(staged.runs(PrepStage::Load), 1);
    EXPECT_EQ(staged.runs(PrepStage::Classify), 2);
    EXPECT_EQ(staged.runs(PrepStage::Segment), 3);
    EXPECT_EQ(staged.runs(PrepStage::Fields), 4);
}

TEST(StagedPreparation, StopsAtTheStageAskedFor) {
    StagedPreparation staged(test::datasetsDir() / kFile);
    PrepareOptions o = headOptions();
    const PreparedVolume& p = staged.prepare(o, PrepStage::Classify);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"load", "classify"}));
    EXPECT_EQ(p.classified.sigma.size(), voxelCount({64, 64, 93}));
    EXPECT_TRUE(p.regions.label.empty());
    EXPECT_FALSE(p.fields.hasPC());
    EXPECT_EQ(staged.volume().values.size(), voxelCount({64, 64, 93}));  // kept for the next classification

    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment", "acd", "pc", "eacd"}));
    // Asking for fewer stages keeps the later results while they are valid ...
    staged.prepare(o, PrepStage::Segment);
    EXPECT_TRUE(staged.lastStages().empty());
    EXPECT_TRUE(p.fields.hasEACD());
    // ... and drops them when they are not.
    o.segmentation.angleThresholdDeg = 40;
    staged.prepare(o, PrepStage::Segment);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment"}));
    EXPECT_FALSE(p.fields.hasEACD());
    EXPECT_FALSE(p.regions.label.empty());
    staged.prepare(o);
    expectSameAsFresh(staged, p, o);

    // Other raw-file options load again (here: a different spacing).
    o.raw.spacing = Vec3d{1, 1, 1};
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()),
              (std::vector<std::string>{"load", "classify", "segment", "acd", "pc", "eacd"}));
    expectSameAsFresh(staged, p, o);
}

TEST(StagedPreparation, AVolumeInMemoryIsNeverLoaded) {
    const Volume engine = enginePhantom({20, 17, 12});
    StagedPreparation staged(engine);
    PrepareOptions o;
    o.raw.spacing = Vec3d{2, 2, 2};  // does not apply
    o.classify.transferFunction = loadTransferFunction(test::datasetsDir() / "sim.tf.json");
    o.segmentation = {0.1, 20, true, true};
    const PreparedVolume& p = staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "acd", "pc", "eacd"}));
    EXPECT_EQ(p.meta.source, engine.source);
    const ClassifiedVolume c = classify(engine, o.classify);
    EXPECT_EQ(p.classified.sigma, c.sigma);
    EXPECT_EQ(p.classified.normal, c.normal);
    EXPECT_EQ(p.regions.label, segment(c, o.segmentation).label);
    std::vector<StageTime> times;
    EXPECT_EQ(p.fields.pc, buildTimedFields(p.regions, kFieldPC, o.eacdCode, times).pc);
    o.classify.normals = false;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "acd", "pc", "eacd"}));
    EXPECT_FALSE(p.classified.hasNormals());
    EXPECT_EQ(staged.runs(PrepStage::Load), 0);
}

TEST(StagedPreparation, AStageThatThrowsRunsAgainNextTime) {
    StagedPreparation staged(test::datasetsDir() / kFile);
    PrepareOptions o = headOptions();
    staged.prepare(o);
    PrepareOptions bad = o;
    bad.segmentation.opacityThreshold = -1;
    EXPECT_THROW(staged.prepare(bad), InputError);
    EXPECT_TRUE(staged.prepare(o).regions.label.size() == voxelCount({64, 64, 93}));
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment", "acd", "pc", "eacd"}));
    expectSameAsFresh(staged, staged.prepare(o), o);

    StagedPreparation missing(test::datasetsDir() / "no_such_volume_8x8x8_uint8.raw.gz");
    EXPECT_THROW(missing.prepare(o), InputError);
    EXPECT_THROW(missing.prepare(o), InputError);
    EXPECT_EQ(missing.runs(PrepStage::Load), 2);
    EXPECT_EQ(missing.runs(PrepStage::Classify), 0);
}

}  // namespace
}  // namespace vr
