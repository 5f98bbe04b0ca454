// Staged preparation: after any sequence of option changes its result equals a fresh prepare(), and a change
// re-runs only the stages that depend on it (a threshold change: segmentation and fields; a TF change:
// classification too).
#include <gtest/gtest.h>

#include <algorithm>

#include "core/errors.h"
#include "datasets/phantoms.h"
#include "preprocess/classify/tf_range_table.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "preprocess/pipeline/working_set.h"
#include "preprocess/segment/segment.h"
#include "render/caster_choice.h"
#include "support/load_dataset.h"

namespace vr {
namespace {

const char* kFile = "vtk_headsq_ct_64x64x93_uint16.raw.gz";

StagedPreparation stagedHead() {
    return StagedPreparation::load(test::datasetsDir() / kFile, test::manifestRawOptions(kFile));
}

// The head CT loaded and prepared at once, as volprep prepares it.
PreparedVolume freshHead(const PrepareOptions& options) {
    return prepare(test::loadDataset(kFile), options);
}

PrepareOptions headOptions() {
    PrepareOptions o;
    o.classify.transferFunction = test::datasetTransferFunction("vtk_headsq_ct.tf.json");
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

// Everything a fresh prepare() produces, compared with the staged result.
void expectSameAsFresh(StagedPreparation& staged, const PrepareOptions& options) {
    const PreparedVolume& p = staged.withStatistics();
    const PreparedVolume f = freshHead(options);
    EXPECT_EQ(p.grid(), f.grid());
    EXPECT_EQ(p.scalars.values, f.scalars.values);
    EXPECT_EQ(p.scalars.sourceType, f.scalars.sourceType);
    EXPECT_EQ(p.classification, f.classification);
    EXPECT_EQ(p.regions.dims, f.regions.dims);
    EXPECT_EQ(p.regions.count, f.regions.count);
    EXPECT_EQ(p.regions.label, f.regions.label);
    EXPECT_EQ(p.fields.dims, f.fields.dims);
    EXPECT_EQ(p.fields.pc, f.fields.pc);
    EXPECT_EQ(p.fields.acd, f.fields.acd);
    EXPECT_EQ(p.fields.eacd, f.fields.eacd);
    EXPECT_EQ(p.meta.source, f.meta.source);
    EXPECT_EQ(p.meta.classification, f.meta.classification);
    EXPECT_EQ(p.meta.segmentation, f.meta.segmentation);
    EXPECT_EQ(p.meta.distanceCap, f.meta.distanceCap);
    EXPECT_EQ(untimed(p.meta.statistics), untimed(f.meta.statistics));
    EXPECT_EQ(p.meta.rayProbe, f.meta.rayProbe);
}

TEST(PipelineStaged, EachChangeReRunsOnlyTheStagesAfterIt) {
    StagedPreparation staged = stagedHead();
    PrepareOptions o = headOptions();
    const PreparedVolume& p = staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "acd", "pc", "eacd"}));
    EXPECT_EQ(names(staged.stageTimes()),
              (std::vector<std::string>{"load", "classify", "segment", "acd", "pc", "eacd"}));
    expectSameAsFresh(staged, o);

    // The same options again: nothing runs.
    EXPECT_EQ(&staged.prepare(o), &p);
    EXPECT_TRUE(staged.lastStages().empty());

    // A threshold change: segmentation and the fields only.
    o.segmentation.opacityThreshold = 0.2;
    o.segmentation.trilinear = true;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment", "acd", "pc", "eacd"}));
    EXPECT_TRUE(p.meta.statistics.is_null());  // they described the old result
    EXPECT_FALSE(p.meta.rayProbe);
    expectSameAsFresh(staged, o);

    // Other fields only: the fields only.
    o.fields = kFieldPC;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"pc"}));
    EXPECT_FALSE(p.fields.hasACD());
    expectSameAsFresh(staged, o);

    // A TF change: classification, segmentation and the fields; the load's time stays first.
    o.classify.transferFunction->opacity.back().opacity = 0.3;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "pc"}));
    EXPECT_EQ(names(staged.stageTimes()), (std::vector<std::string>{"load", "classify", "segment", "pc"}));
    expectSameAsFresh(staged, o);

    // Only the TF's name and text (not what it says) changed: no stage runs, the metadata follows.
    o.classify.transferFunction->name += " renamed";
    o.classify.transferFunction->json += " ";
    staged.prepare(o);
    EXPECT_TRUE(staged.lastStages().empty());
    EXPECT_EQ(p.meta.classification, o.classify.transferFunction->json);
    // Any other parameter of the classification classifies again.
    o.classify.flatGradientFloor *= 2;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "pc"}));

    EXPECT_EQ(staged.runs(PrepStage::Classify), 3);
    EXPECT_EQ(staged.runs(PrepStage::Segment), 4);
    EXPECT_EQ(staged.runs(PrepStage::Fields), 5);
}

TEST(PipelineStaged, StopsAtTheStageAskedFor) {
    StagedPreparation staged = stagedHead();
    PrepareOptions o = headOptions();
    const PreparedVolume& p = staged.prepare(o, PrepStage::Classify);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify"}));
    const auto [lo, hi] = std::minmax_element(staged.volume().values.begin(), staged.volume().values.end());
    EXPECT_EQ(p.classification.table.size(), std::size_t(*hi - *lo + 1));  // an entry per integer in the range
    EXPECT_TRUE(p.regions.label.empty());
    EXPECT_FALSE(p.fields.hasPC());
    EXPECT_EQ(staged.volume().values.size(), voxelCount({64, 64, 93}));

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
    expectSameAsFresh(staged, o);
}

TEST(PipelineStaged, AVolumeInMemoryIsNeverLoaded) {
    const Volume engine = enginePhantom({20, 17, 12});
    StagedPreparation staged(engine);
    PrepareOptions o;
    o.classify.transferFunction = test::datasetTransferFunction("sim.tf.json");
    o.segmentation = {0.1, 20, true, true};
    const PreparedVolume& p = staged.prepare(o);
    EXPECT_EQ(names(staged.stageTimes()), (std::vector<std::string>{"classify", "segment", "acd", "pc", "eacd"}));
    EXPECT_EQ(p.meta.source, engine.source);
    EXPECT_EQ(p.scalars.values, engine.values);
    EXPECT_EQ(p.classification, scalarClassification(engine, o.classify));
    // Trilinear from a transfer function: regions for post-classification, built on the scalars; the voxels
    // classified on demand segment as the classified volume does.
    const TfRangeTable spread(sampleForVolume(engine, *o.classify.transferFunction));
    EXPECT_EQ(p.regions.label,
              segment(classify(engine, o.classify), o.segmentation, ClassifiedScalars{engine.values, spread}).label);
    EXPECT_EQ(p.fields.pc, buildFields(p.regions, kFieldPC).pc);
    o.classify.normals = false;
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"classify", "segment", "acd", "pc", "eacd"}));
    EXPECT_EQ(p.regions.label,
              segment(classify(engine, o.classify), o.segmentation, ClassifiedScalars{engine.values, spread}).label);
}

TEST(PipelineStaged, AStageThatThrowsRunsAgainNextTime) {
    StagedPreparation staged = stagedHead();
    PrepareOptions o = headOptions();
    staged.prepare(o);
    PrepareOptions bad = o;
    bad.segmentation.opacityThreshold = -1;
    EXPECT_THROW(staged.prepare(bad), InputError);
    EXPECT_TRUE(staged.prepare(o).regions.label.size() == voxelCount({64, 64, 93}));
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment", "acd", "pc", "eacd"}));
    expectSameAsFresh(staged, o);

    EXPECT_THROW(StagedPreparation::load(test::datasetsDir() / "no_such_volume_8x8x8_uint8.raw.gz", {}),
                 InputError);
}

// Segmentation classifies the voxels from the scalars as it reads them: a threshold change segments again without
// classifying again, and gives back the first regions when the thresholds return.
TEST(PipelineStaged, SegmentsAgainWithoutClassifyingAgain) {
    StagedPreparation staged = stagedHead();
    PrepareOptions o = headOptions();
    const PreparedVolume& p = staged.prepare(o);
    EXPECT_FALSE(p.scalars.values.empty());  // the renderers classify from them
    const std::vector<uint32_t> labels = p.regions.label;
    o.segmentation = {0.5, 180, true, true};
    staged.prepare(o);
    EXPECT_EQ(names(staged.lastStages()), (std::vector<std::string>{"segment", "acd", "pc", "eacd"}));
    EXPECT_NE(p.regions.label, labels);
    o = headOptions();
    staged.prepare(o);
    EXPECT_EQ(p.regions.label, labels);
    EXPECT_EQ(staged.runs(PrepStage::Classify), 1);
}

// A render that needs only the fields lets the builder free the labels: the same fields, no regions left, and a
// later preparation segments again.
TEST(PipelineStaged, FieldsWithoutKeepingTheRegions) {
    StagedPreparation kept = stagedHead(), freed = stagedHead();
    PrepareOptions o = headOptions();
    o.fields = kFieldEACD;
    o.octants = 0x21;
    const PreparedVolume& k = kept.prepare(o);
    o.keepRegions = false;
    const PreparedVolume& f = freed.prepare(o);
    EXPECT_TRUE(f.regions.label.empty());
    EXPECT_EQ(f.regions.count, 0u);
    for (int oct = 0; oct < kOctants; ++oct) EXPECT_EQ(f.fields.eacd[oct], k.fields.eacd[oct]) << oct;
    freed.prepare(o);
    EXPECT_EQ(names(freed.lastStages()), (std::vector<std::string>{"segment", "acd", "eacd"}));
    o.keepRegions = true;
    freed.prepare(o);
    EXPECT_EQ(f.regions.label, k.regions.label);
}

// A volume whose preparation would not fit the memory allowed is refused before any stage runs, with the estimate
// and the limit; the estimate grows with what is asked.
TEST(PipelineStaged, AVolumeTooLargeForTheMemoryIsRefusedBeforeAnyStage) {
    StagedPreparation staged(enginePhantom({20, 17, 12}));
    PrepareOptions o;
    o.classify.transferFunction = test::datasetTransferFunction("sim.tf.json");
    const std::size_t needed = preparationBytes(staged.volume().grid, o);
    o.memoryLimit = needed - 1;
    try {
        staged.prepare(o);
        ADD_FAILURE() << "not refused";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("preparing 20x17x12 voxels needs about"), std::string::npos) << what;
        EXPECT_NE(what.find("allowed"), std::string::npos) << what;
    }
    EXPECT_EQ(staged.runs(PrepStage::Classify), 0);
    EXPECT_TRUE(staged.lastStages().empty());
    o.memoryLimit = needed;
    EXPECT_NO_THROW(staged.prepare(o));

    PrepareOptions less = o;
    less.fields = kFieldEACD;
    less.octants = 1;
    less.classify.normals = false;
    less.segmentation.trilinear = false;
    EXPECT_LT(preparationBytes(staged.volume().grid, less), needed);
    EXPECT_GT(availableMemoryBytes(), 0u);
}

// volprep's stages: the ray probe, the statistics and the write last, each timed; the statistics the file holds have
// the probe's time and cannot have their own or the write's.
TEST(PipelineStaged, WritesTheResultWithItsStatisticsAsTheLastStage) {
    StagedPreparation staged = stagedHead();
    const PrepareOptions o = headOptions();
    staged.prepare(o);
    const std::filesystem::path file = test::scratchDir("pipeline_staged_write") / "head.vprep";
    staged.write(file);
    EXPECT_EQ(names(staged.stageTimes()),
              (std::vector<std::string>{"load", "classify", "segment", "acd", "pc", "eacd", "probe", "statistics",
                                        "write"}));
    const PreparedVolume& p = staged.withStatistics();
    EXPECT_TRUE(p.meta.statistics["seconds"].contains("probe"));
    EXPECT_FALSE(p.meta.statistics["seconds"].contains("statistics"));
    EXPECT_FALSE(p.meta.statistics["seconds"].contains("write"));
    ASSERT_TRUE(p.meta.rayProbe);
    EXPECT_EQ(p.meta.rayProbe, probeRays(p));  // the render core's probe of the result
    EXPECT_TRUE(std::filesystem::is_regular_file(file));
}

}  // namespace
}  // namespace vr
