#include "preprocess/pipeline/staged_prepare.h"

#include <bit>
#include <sstream>
#include <stdexcept>

#include "io/prepared_file.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/prepared_statistics.h"
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

// The classification as text for the metadata: the TF's JSON, or "iso value,width,strength; ...".
std::string classificationText(const ClassifyParams& params) {
    if (params.transferFunction) return params.transferFunction->json;
    std::ostringstream s;
    s.precision(17);
    s << "iso";
    for (std::size_t i = 0; i < params.isoContours.size(); ++i) {
        const IsoContour& c = params.isoContours[i];
        s << (i ? "; " : " ") << c.value << "," << c.width << "," << c.strength;
    }
    return s.str();
}

// The fields of `kinds` (a FieldKind mask), with a progress bar and each field timed into `times`.
DistanceFields buildTimedFields(const Regions& regions, unsigned kinds, ExtentCode eacdCode,
                                std::vector<StageTime>& times) {
    // One call builds them all, sharing the axial runs and the ACDs: each field is timed from the end of the one
    // before (ACD first, then PC from the ACDs, then EACD).
    const unsigned built = (kinds & kFieldEACD ? kinds | kFieldACD : kinds) & (kFieldPC | kFieldACD | kFieldEACD);
    ProgressBar bar("fields", std::popcount(built));
    StageClock clock;
    // The EACD is written in eacdCode as it is built: memory, file and device then hold the same bytes.
    DistanceFields f = buildFields(regions, kinds, eacdCode, [&](FieldKind kind) {
        times.push_back(clock.stop(kind == kFieldPC ? "pc" : kind == kFieldACD ? "acd" : "eacd"));
        bar.advance();
        clock = StageClock();
    });
    bar.finish();
    return f;
}

// Trilinear regions from a transfer function are built on the scalars (post-classification, section 9).
bool segmentsScalars(const PrepareOptions& options) {
    return options.segmentation.trilinear && options.classify.transferFunction.has_value();
}

}  // namespace

StagedPreparation::StagedPreparation(Volume volume, ScalarsOnceClassified scalars)
    : volume_(std::move(volume)), scalarsOnceClassified_(scalars) {
    prepared_.meta.source = volume_.source;
    prepared_.meta.distanceCap = kDistanceCap;
}

StagedPreparation StagedPreparation::load(const std::filesystem::path& input, const RawOptions& raw,
                                          ScalarsOnceClassified scalars) {
    std::vector<StageTime> times;
    StagedPreparation staged(runStage("load", times, [&] { return loadVolume(input, raw); }), scalars);
    staged.loadTimes_ = std::move(times);
    return staged;
}

void StagedPreparation::invalidateFrom(PrepStage stage) {
    switch (stage) {  // each case falls through to the stages after it
        case PrepStage::Classify:
            classifiedWith_.reset();
            if (!prepared_.classified.sigma.empty())  // its memory serves the next classification (likewise below)
                spareClassified_ = std::exchange(prepared_.classified, {});
            [[fallthrough]];
        case PrepStage::Segment:
            segmentedWith_.reset();
            if (!prepared_.regions.label.empty()) spareRegions_ = std::exchange(prepared_.regions, {});
            [[fallthrough]];
        case PrepStage::Fields:
            fieldsWith_.reset();
            prepared_.fields = {};
    }
    for (int s = int(stage); s < kPrepStages; ++s) times_[s].clear();
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
    ClassifyParams classifying = classifyingPart(options.classify);
    if (classifiedWith_ != classifying) {
        if (scalarsFreed_) throw std::logic_error("StagedPreparation: the scalars were freed once classified");
        run(PrepStage::Classify, [&](std::vector<StageTime>& times) {
            runStage("classify", times, [&] { classify(volume_, options.classify, spareClassified_); });
            prepared_.classified = std::exchange(spareClassified_, {});
        });
        classifiedWith_ = std::move(classifying);
        if (!segmentsScalars(options)) freeScalarsIfAsked();
    }
    prepared_.meta.classification = classificationText(options.classify);  // the TF's text may differ
    if (last >= PrepStage::Segment && segmentedWith_ != options.segmentation) {
        if (segmentsScalars(options) && scalarsFreed_)
            throw std::logic_error("StagedPreparation: the scalars were freed before a trilinear segmentation");
        run(PrepStage::Segment, [&](std::vector<StageTime>& times) {
            runStage("segment", times, [&] {
                if (!segmentsScalars(options))
                    return segment(prepared_.classified, options.segmentation, spareRegions_);
                const TfRangeTable spread(transferTable(volume_, *options.classify.transferFunction));
                segment(prepared_.classified, options.segmentation, ClassifiedScalars{volume_.values, spread},
                        spareRegions_);
            });
            prepared_.regions = std::exchange(spareRegions_, {});
        });
        segmentedWith_ = options.segmentation;
        freeScalarsIfAsked();
        prepared_.meta.segmentation = options.segmentation;
    }
    const std::pair<unsigned, ExtentCode> fields{options.fields, options.eacdCode};
    if (last >= PrepStage::Fields && fieldsWith_ != fields) {
        run(PrepStage::Fields, [&](std::vector<StageTime>& times) {
            prepared_.fields = buildTimedFields(prepared_.regions, options.fields, options.eacdCode, times);
        });
        fieldsWith_ = fields;
    }
    return prepared_;
}

void StagedPreparation::freeScalarsIfAsked() {
    if (scalarsOnceClassified_ != ScalarsOnceClassified::Free) return;
    volume_ = {};
    scalarsFreed_ = true;
}

const PreparedVolume& StagedPreparation::withStatistics() {
    if (prepared_.meta.statistics.is_null()) {
        prepared_.meta.statistics = preparedStatistics(prepared_, stageTimes());
        prepared_.meta.rayProbe = probeRays(prepared_);
    }
    return prepared_;
}

void StagedPreparation::write(const std::filesystem::path& path) {
    const PreparedVolume& prepared = withStatistics();  // before the write's time: the file cannot hold that
    writeTimes_.clear();
    runStage("write", writeTimes_, [&] { writePrepared(path, prepared); });
}

std::vector<StageTime> StagedPreparation::stageTimes() const {
    std::vector<StageTime> times = loadTimes_;
    for (const auto& t : times_) times.insert(times.end(), t.begin(), t.end());
    times.insert(times.end(), writeTimes_.begin(), writeTimes_.end());
    return times;
}

PreparedVolume prepare(Volume volume, const PrepareOptions& options) {
    StagedPreparation staged(std::move(volume), ScalarsOnceClassified::Free);
    staged.prepare(options);
    staged.withStatistics();
    return std::move(staged).takeResult();
}

}  // namespace vr
