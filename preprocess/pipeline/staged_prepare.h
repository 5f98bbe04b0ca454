// The preprocessing pipeline over a volume in memory: classify -> segment -> distance fields, each stage timed with
// a progress bar (shown on a terminal only). It keeps every stage's result, and when asked again with other options
// re-runs only the stages whose inputs changed and those after them: a threshold change re-runs segmentation and
// the fields, a transfer-function change classification too. volprep, volsweep and the benchmarks all run it.
// The result holds the scalars and the tabulated TF, which the renderers classify each sample from; segmentation
// classifies each voxel as it reads it (ClassifiedVoxels), so no classified copy of the volume is ever held.
#pragma once
#include <array>
#include <filesystem>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "core/prepared_volume.h"
#include "preprocess/classify/classify.h"
#include "preprocess/load/load_volume.h"
#include "preprocess/pipeline/stage_time.h"

namespace vr {

struct PrepareOptions {
    ClassifyParams classify;           // the transfer function
    SegmentationParams segmentation;   // T_o, T_a, useNormals, trilinear
    unsigned fields = kFieldPC | kFieldACD | kFieldEACD;  // kFieldHier too where asked (a render's: not in a file)
    ExtentCode eacdCode = kDefaultExtentCode;  // EACD extents rounded down to this code (core/extent_code.h)
    unsigned octants = kAllOctants;  // ACD and EACD octants to build: all for a file, a render's views' otherwise
    std::size_t memoryLimit = 0;     // bytes the first preparation may need (working_set.h); 0: what is available
    // Whether the regions are kept once the fields are built: a render that needs only the fields gives their
    // labels to the fields builder, which frees them as soon as it can (a later prepare() segments again).
    bool keepRegions = true;
};

// The stages in the order they depend on each other.
enum class PrepStage { Classify, Segment, Fields };
constexpr int kPrepStages = 3;

class StagedPreparation {
public:
    // meta.source is volume.source.
    explicit StagedPreparation(Volume volume);
    // Loads `input` (loadVolume, `raw` for headerless raw files) as the stage "load": the first of stageTimes().
    // Throws InputError as loadVolume does.
    static StagedPreparation load(const std::filesystem::path& input, const RawOptions& raw);

    // Attaches a label map on the volume's grid, its classes chosen (classified here, for the transfer function's
    // reference step): every stage runs again with it (docs/ALGORITHMS.md section 2, label maps).
    void setLabels(LabelMap labels);

    // Brings the stages up to `last` up to date with `options` and returns the result. Each field is timed on its
    // own: ACD (the 8 octant passes, also built when only EACD is asked for), PC from the ACDs, EACD on top of ACD.
    // Stages after `last` do not run, and keep their results only while these are still valid (else they are
    // empty). The first call refuses a volume whose preparation would need more memory than options.memoryLimit
    // allows (requireWorkingSetFits), before any stage runs. Throws InputError for bad parameters; a stage that
    // threw runs again on the next call. The reference stays valid for the lifetime of this object.
    const PreparedVolume& prepare(const PrepareOptions& options, PrepStage last = PrepStage::Fields);

    // The result with meta.rayProbe (probeRays: a few hundred small CPU renders, timed as the stage "probe") and
    // meta.statistics (preparedStatistics, with stageTimes() up to the probe; timed as the stage "statistics") filled
    // in, as a prepared file holds them; until a stage runs again.
    const PreparedVolume& withStatistics();
    // Writes withStatistics() to `path` atomically (writePrepared) as the stage "write": the last of stageTimes()
    // until a stage runs again. Throws InputError where the file cannot be written.
    void write(const std::filesystem::path& path);
    // The result, moved out of a preparation that is done with.
    PreparedVolume takeResult() && { return std::move(prepared_); }

    // The stages the last prepare() ran, in order (classify, segment, acd, pc, eacd); empty when nothing had changed.
    const std::vector<StageTime>& lastStages() const { return lastStages_; }
    // The times of the stage runs behind the current result, in order: "load" first where it ran, then "probe",
    // "statistics" and "write" last where they ran.
    std::vector<StageTime> stageTimes() const;
    // How many times `stage` has run since construction (a stage that threw included).
    int runs(PrepStage stage) const { return runs_[int(stage)]; }
    // The scalars.
    const Volume& volume() const { return prepared_.scalars; }

private:
    // Discards the results of `stage` and of every stage after it (the regions' labels are kept aside for the next
    // segmentation to reuse: no fresh pages to fault in).
    void invalidateFrom(PrepStage stage);
    // Runs `work` as `stage`, counting it; `work` appends its times.
    template <typename Work>
    void run(PrepStage stage, Work work);

    PreparedVolume prepared_;    // prepared_.scalars: the volume
    Regions spareRegions_;         // invalidated regions, whose labels the next segmentation reuses
    // The options each stage last ran with; empty when it has no valid result.
    std::optional<ClassifyParams> classifiedWith_;  // as far as they classify (the TF's name and text left out)
    std::optional<SegmentationParams> segmentedWith_;
    // Kinds, EACD code, octants and, for the hier field, which reads no regions, the segmentation's parameters.
    using FieldsOptions = std::tuple<unsigned, ExtentCode, unsigned, SegmentationParams>;
    std::optional<FieldsOptions> fieldsWith_;
    std::vector<StageTime> loadTimes_;                           // of loading the volume, where it was loaded
    std::array<std::vector<StageTime>, kPrepStages> times_;      // of the run behind each stage's result
    std::vector<StageTime> statisticsTimes_;                     // of the current result's probe and statistics
    std::vector<StageTime> writeTimes_;                          // of writing the current result
    std::array<int, kPrepStages> runs_{};
    std::vector<StageTime> lastStages_;
};

// Every stage once over `volume`, with the statistics and the ray probe: the prepared volume as volprep writes it
// (StagedPreparation for the stages' times).
PreparedVolume prepare(Volume volume, const PrepareOptions& options);

}  // namespace vr
