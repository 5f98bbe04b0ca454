#include "preprocess/pipeline/staged_prepare.h"

#include <algorithm>

#include "io/prepared_file.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/hier_field.h"
#include "preprocess/pipeline/prepared_statistics.h"
#include "preprocess/pipeline/working_set.h"
#include "preprocess/classify/label_colours.h"
#include "preprocess/classify/tf_range_table.h"
#include "preprocess/segment/segment.h"
#include "render/caster_choice.h"

namespace vr {
namespace {

// The parameters as far as they classify: the TF's name and JSON text only go to the metadata. Whatever else a
// parameter struct holds is compared, so that a new parameter can never leave a stale classification.
ClassifyParams classifyingPart(ClassifyParams params) {
    if (params.transferFunction) {
        params.transferFunction->name.clear();
        params.transferFunction->json.clear();
    }
    return params;
}

// The fields of `kinds` (a FieldKind mask), with a progress bar and each field timed into `times`. `regions` is
// consumed when it is an rvalue.
template <typename RegionsRef>
DistanceFields buildTimedFields(RegionsRef&& regions, unsigned kinds, ExtentCode eacdCode, unsigned octants,
                                std::vector<StageTime>& times) {
    // One call builds them all, sharing the axial runs and the ACDs: each field is timed from the end of the one
    // before (ACD first, then PC from the ACDs, then EACD).
    ProgressBar bar("fields", 1);
    StageClock clock;
    // The EACD is written in eacdCode as it is built: memory, file and device then hold the same bytes.
    DistanceFields f = buildFields(
        std::forward<RegionsRef>(regions), kinds, eacdCode,
        [&](FieldKind kind) {
            times.push_back(clock.stop(kind == kFieldPC ? "pc" : kind == kFieldACD ? "acd" : "eacd"));
            clock = StageClock();
        },
        octants, bar.report());
    bar.finish();
    return f;
}

}  // namespace

StagedPreparation::StagedPreparation(Volume volume) {
    prepared_.scalars = std::move(volume);
    prepared_.meta.source = prepared_.scalars.source;
    prepared_.meta.distanceCap = kDistanceCap;
}

StagedPreparation StagedPreparation::load(const std::filesystem::path& input, const RawOptions& raw) {
    std::vector<StageTime> times;
    StagedPreparation staged(runStage("load", times, [&] { return loadVolume(input, raw); }));
    staged.loadTimes_ = std::move(times);
    return staged;
}

void StagedPreparation::setLabels(LabelMap labels) {
    invalidateFrom(PrepStage::Classify);
    prepared_.labels = std::move(labels);
}

void StagedPreparation::invalidateFrom(PrepStage stage) {
    switch (stage) {  // each case falls through to the stages after it
        case PrepStage::Classify:
            classifiedWith_.reset();
            prepared_.classification = {};
            [[fallthrough]];
        case PrepStage::Segment:
            segmentedWith_.reset();
            if (!prepared_.regions.label.empty())  // its memory serves the next segmentation
                spareRegions_ = std::exchange(prepared_.regions, {});
            [[fallthrough]];
        case PrepStage::Fields:
            fieldsWith_.reset();
            prepared_.fields = {};
    }
    for (int s = int(stage); s < kPrepStages; ++s) times_[s].clear();
    statisticsTimes_.clear();
    writeTimes_.clear();
    prepared_.meta.statistics = {};
    prepared_.meta.rayProbe.reset();
}

template <typename Work>
void StagedPreparation::run(PrepStage stage, Work work) {
    invalidateFrom(stage);  // first: the old results go before the new ones are built, and stay gone on a throw
    ++runs_[int(stage)];
    std::vector<StageTime>& times = times_[int(stage)];
    work(times);
    lastStages_.insert(lastStages_.end(), times.begin(), times.end());
}

const PreparedVolume& StagedPreparation::prepare(const PrepareOptions& options, PrepStage last) {
    lastStages_.clear();
    if (runs_[int(PrepStage::Classify)] == 0)  // before any work: a volume too large is refused, not killed halfway
        requireWorkingSetFits(prepared_.meta.source.empty() ? "preparation" : prepared_.meta.source,
                              prepared_.grid(), options, options.memoryLimit);
    ClassifyParams classifying = classifyingPart(options.classify);
    if (classifiedWith_ != classifying) {
        run(PrepStage::Classify, [&](std::vector<StageTime>& times) {
            runStage("classify", times, [&] {
                prepared_.classification = scalarClassification(prepared_.scalars, options.classify);
                if (prepared_.labels)
                    prepared_.labels->classes =
                        classifyLabels(prepared_.labels->rgba, prepared_.classification.referenceStep);
            });
        });
        classifiedWith_ = std::move(classifying);
    }
    if (options.classify.transferFunction) prepared_.meta.classification = options.classify.transferFunction->json;
    // Regions that nothing reads are not made: no field asks for them and they are not kept (the hier field is
    // built from the scalars).
    if (!options.fields && !options.keepRegions) last = std::min(last, PrepStage::Classify);
    const bool regionsRead = (options.fields & kRegionFields) || options.keepRegions;
    if (last >= PrepStage::Segment && regionsRead && segmentedWith_ != options.segmentation) {
        run(PrepStage::Segment, [&](std::vector<StageTime>& times) {
            runStage("segment", times, [&](const Progress& progress) {
                const ClassifiedVoxels voxels(prepared_.scalars, prepared_.classification, options.classify.normals,
                                              prepared_.labels ? &*prepared_.labels : nullptr);
                if (!options.segmentation.trilinear)
                    return segment(voxels, options.segmentation, spareRegions_, progress);
                // Post-classification (docs/ALGORITHMS.md section 9): regions over the scalars' intervals.
                const TfRangeTable spread(sampleForVolume(prepared_.scalars, *options.classify.transferFunction));
                segment(voxels, options.segmentation, ClassifiedScalars{prepared_.scalars.values, spread},
                        spareRegions_, progress);
            });
            prepared_.regions = std::exchange(spareRegions_, {});
        });
        segmentedWith_ = options.segmentation;
        prepared_.meta.segmentation = options.segmentation;
    }
    const FieldsOptions fields{options.fields, options.eacdCode, options.octants, options.segmentation};
    if (last >= PrepStage::Fields && fieldsWith_ != fields) {
        run(PrepStage::Fields, [&](std::vector<StageTime>& times) {
            if (options.fields & kRegionFields)
                prepared_.fields =
                    options.keepRegions
                        ? buildTimedFields(prepared_.regions, options.fields, options.eacdCode, options.octants, times)
                        : buildTimedFields(std::exchange(prepared_.regions, {}), options.fields, options.eacdCode,
                                           options.octants, times);
            if (options.fields & kFieldHier) {
                prepared_.fields.dims = prepared_.grid().dims;
                prepared_.meta.segmentation = options.segmentation;  // what the render checks ask of it
                prepared_.fields.hier = runStage("hier", times, [&] {
                    return buildHierarchicalEACD(prepared_, options.segmentation, options.octants);
                });
            }
        });
        fieldsWith_ = fields;
        if (!options.keepRegions) segmentedWith_.reset();  // the regions are gone: segment again when asked
    }
    return prepared_;
}

const PreparedVolume& StagedPreparation::withStatistics() {
    if (prepared_.meta.statistics.is_null()) {
        // Both timed as stages, with their bars: the statistics read every field (0.8 s of a 512^3 CT's preparation,
        // between the fields and the write with no bar), and cannot hold their own time, as the write cannot.
        statisticsTimes_.clear();
        prepared_.meta.rayProbe = runStage("probe", statisticsTimes_, [&] { return probeRays(prepared_); });
        prepared_.meta.statistics =
            runStage("statistics", statisticsTimes_, [&] { return preparedStatistics(prepared_, stageTimes()); });
    }
    return prepared_;
}

void StagedPreparation::write(const std::filesystem::path& path) {
    const PreparedVolume& prepared = withStatistics();  // before the write's time: the file cannot hold that
    writeTimes_.clear();
    runStage("write", writeTimes_, [&](const Progress& progress) {
        PreparedWriteOptions options;
        options.progress = progress;
        writePrepared(path, prepared, options);
    });
}

std::vector<StageTime> StagedPreparation::stageTimes() const {
    std::vector<StageTime> times = loadTimes_;
    for (const auto& t : times_) times.insert(times.end(), t.begin(), t.end());
    times.insert(times.end(), statisticsTimes_.begin(), statisticsTimes_.end());
    times.insert(times.end(), writeTimes_.begin(), writeTimes_.end());
    return times;
}

PreparedVolume prepare(Volume volume, const PrepareOptions& options) {
    StagedPreparation staged(std::move(volume));
    staged.prepare(options);
    staged.withStatistics();
    return std::move(staged).takeResult();
}

}  // namespace vr
