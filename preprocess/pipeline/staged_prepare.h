// Preparation that pays only for what changes: it keeps the loaded volume, the classification, the regions and the
// fields, and when asked again with other options re-runs only the stages whose inputs changed and those after
// them. A threshold change re-runs segmentation and the fields, a transfer-function change classification too;
// the file is loaded once (again only when the raw-file options change).
#pragma once
#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "preprocess/pipeline/prepare.h"

namespace vr {

// The stages in the order they depend on each other.
enum class PrepStage { Load, Classify, Segment, Fields };
constexpr int kPrepStages = 4;

class StagedPreparation {
public:
    explicit StagedPreparation(std::filesystem::path input);
    // A volume already in memory (a phantom, a resampled volume): the load stage never runs and options.raw does
    // not apply; meta.source is volume.source.
    explicit StagedPreparation(Volume volume);

    // Brings the stages up to `last` up to date with `options` and returns the result. With last = Fields it
    // equals prepareVolume(input, options) but for meta.statistics (see statistics()); stages after `last` do not
    // run, and keep their results only while these are still valid (else they are empty). Throws InputError as
    // prepareVolume does; a stage that threw runs again on the next call. The reference stays valid for the
    // lifetime of this object.
    const PreparedVolume& prepare(const PrepareOptions& options, PrepStage last = PrepStage::Fields);

    // The stages the last prepare() ran, in order (load, classify, segment, pc, acd, eacd); empty when nothing
    // had changed.
    const std::vector<StageTime>& lastStages() const { return lastStages_; }
    // How many times `stage` has run since construction (a stage that threw included).
    int runs(PrepStage stage) const { return runs_[int(stage)]; }
    // preparedStatistics of the current result, with the times of the stage runs that produced it.
    nlohmann::json statistics() const;
    // The loaded scalars (kept for the next classification).
    const Volume& volume() const { return volume_; }

private:
    // Discards the results of `stage` and of every stage after it (the classification's and the regions' arrays
    // are kept aside for the next run of their stage to reuse: no fresh pages to fault in).
    void invalidateFrom(PrepStage stage);
    // Runs `work` as `stage` (named `name` in the times), counting and timing it.
    template <typename Work>
    void run(PrepStage stage, const char* name, Work work);

    std::filesystem::path input_;  // empty for a volume given in memory
    Volume volume_;
    PreparedVolume prepared_;
    // Invalidated results, whose arrays the next run of their stage reuses.
    ClassifiedVolume spareClassified_;
    Regions spareRegions_;
    // The options each stage last ran with; empty when it has no valid result.
    std::optional<RawOptions> loadedWith_;
    std::optional<ClassifyParams> classifiedWith_;
    std::optional<SegmentationParams> segmentedWith_;
    std::optional<std::pair<unsigned, ExtentCode>> fieldsWith_;  // kinds, EACD code
    std::array<std::vector<StageTime>, kPrepStages> times_;      // of the run behind each stage's result
    std::array<int, kPrepStages> runs_{};
    std::vector<StageTime> lastStages_;
};

}  // namespace vr
