#include "preprocess/pipeline/staged_prepare.h"

#include <utility>

#include "preprocess/segment/segment.h"

namespace vr {
namespace {

bool sameRaw(const RawOptions& a, const RawOptions& b) {
    return a.dims == b.dims && a.type == b.type && a.spacing == b.spacing && a.bigEndian == b.bigEndian;
}

// Whether two sets of parameters classify alike: the TF's name and JSON text only go to the metadata.
bool sameClassification(const ClassifyParams& a, const ClassifyParams& b) {
    if (a.transferFunction.has_value() != b.transferFunction.has_value()) return false;
    if (a.transferFunction) {
        const TransferFunction &s = *a.transferFunction, &t = *b.transferFunction;
        if (s.opacity != t.opacity || s.colour != t.colour || s.colourSpace != t.colourSpace) return false;
    }
    return a.isoContours == b.isoContours && a.isoColour == b.isoColour && a.normals == b.normals &&
           a.referenceStep == b.referenceStep && a.flatGradientFloor == b.flatGradientFloor;
}

bool sameSegmentation(const SegmentationParams& a, const SegmentationParams& b) {
    return a.opacityThreshold == b.opacityThreshold && a.angleThresholdDeg == b.angleThresholdDeg &&
           a.useNormals == b.useNormals && a.trilinear == b.trilinear;
}

}  // namespace

StagedPreparation::StagedPreparation(std::filesystem::path input) : input_(std::move(input)) {
    prepared_.meta.source = input_.string();
    prepared_.meta.distanceCap = kDistanceCap;
}

StagedPreparation::StagedPreparation(Volume volume) : volume_(std::move(volume)) {
    prepared_.meta.source = volume_.source;
    prepared_.meta.distanceCap = kDistanceCap;
}

void StagedPreparation::invalidateFrom(PrepStage stage) {
    switch (stage) {  // each case falls through to the stages after it
        case PrepStage::Load:
            loadedWith_.reset();
            volume_ = {};
            [[fallthrough]];
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
}

template <typename Work>
void StagedPreparation::run(PrepStage stage, const char* name, Work work) {
    invalidateFrom(stage);  // first: the old results go before the new ones are built, and stay gone on a throw
    ++runs_[int(stage)];
    std::vector<StageTime>& times = times_[int(stage)];
    StageClock clock;
    work(times);
    if (name) times.push_back(clock.stop(name));
    lastStages_.insert(lastStages_.end(), times.begin(), times.end());
}

const PreparedVolume& StagedPreparation::prepare(const PrepareOptions& options, PrepStage last) {
    lastStages_.clear();
    if (!input_.empty() && (!loadedWith_ || !sameRaw(*loadedWith_, options.raw))) {
        run(PrepStage::Load, "load", [&](std::vector<StageTime>&) { volume_ = loadVolume(input_, options.raw); });
        loadedWith_ = options.raw;
    }
    if (last >= PrepStage::Classify) {
        if (!classifiedWith_ || !sameClassification(*classifiedWith_, options.classify)) {
            run(PrepStage::Classify, "classify", [&](std::vector<StageTime>&) {
                classify(volume_, options.classify, spareClassified_);
                prepared_.classified = std::exchange(spareClassified_, {});
            });
            classifiedWith_ = options.classify;
        }
        prepared_.meta.classification = classificationText(options.classify);  // the TF's text may differ
    }
    if (last >= PrepStage::Segment &&
        (!segmentedWith_ || !sameSegmentation(*segmentedWith_, options.segmentation))) {
        run(PrepStage::Segment, "segment", [&](std::vector<StageTime>&) {
            segment(prepared_.classified, options.segmentation, spareRegions_);
            prepared_.regions = std::exchange(spareRegions_, {});
        });
        segmentedWith_ = options.segmentation;
        prepared_.meta.segmentation = options.segmentation;
    }
    const std::pair<unsigned, ExtentCode> fields{options.fields, options.eacdCode};
    if (last >= PrepStage::Fields && fieldsWith_ != fields) {
        run(PrepStage::Fields, nullptr, [&](std::vector<StageTime>& times) {
            prepared_.fields = buildTimedFields(prepared_.regions, options.fields, options.eacdCode, times);
        });
        fieldsWith_ = fields;
    }
    return prepared_;
}

nlohmann::json StagedPreparation::statistics() const {
    std::vector<StageTime> times;
    for (const auto& t : times_) times.insert(times.end(), t.begin(), t.end());
    return preparedStatistics(prepared_, times);
}

}  // namespace vr
