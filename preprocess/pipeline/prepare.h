// The preprocessing pipeline shared by volprep and the benchmarks: load -> classify -> segment -> fields -> write,
// timing every stage and recording what it produced in the prepared file's statistics.
#pragma once
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "preprocess/classify/classify.h"
#include "preprocess/load/load_volume.h"

namespace vr {

struct PrepareOptions {
    RawOptions raw;                    // for headerless raw inputs
    ClassifyParams classify;           // a transfer function or iso-contours
    SegmentationParams segmentation;   // T_o, T_a, useNormals, trilinear
    unsigned fields = kFieldPC | kFieldACD | kFieldEACD;
    ExtentCode eacdCode = kDefaultExtentCode;  // EACD extents rounded down to this code (core/extent_code.h)
};

struct StageTime {
    std::string stage;   // load, classify, segment, acd, pc, eacd, write
    double seconds;      // wall time
    double cpuSeconds;   // CPU time of the whole process (all threads) meanwhile: steadier on a shared machine
};

// Measures a stage from construction to stop(): wall time and this process's CPU time.
class StageClock {
public:
    StageClock();
    StageTime stop(std::string stage) const;

private:
    std::chrono::steady_clock::time_point wall_;
    double cpu_;
};

struct PrepareResult {
    PreparedVolume prepared;         // meta.statistics filled (see preparedStatistics)
    std::vector<StageTime> stages;   // in the order they ran
    std::uintmax_t fileBytes = 0;    // size of the written file (prepareFile only)
};

// Runs every stage up to the distance fields, with a progress bar per stage (shown on a terminal only).
// Each field is timed on its own: PC alone (its own ACD passes), ACD (the 8 octant passes, also built when only
// EACD is asked for), EACD on top of ACD. Throws InputError for bad input or parameters.
PrepareResult prepareVolume(const std::filesystem::path& input, const PrepareOptions& options);

// prepareVolume, then writes the prepared file atomically (nothing is left at `output` on failure).
PrepareResult prepareFile(const std::filesystem::path& input, const std::filesystem::path& output,
                          const PrepareOptions& options);

// The fields of `kinds` (a FieldKind mask) as prepareVolume builds them, each timed into `stages` (acd, pc, eacd: PC is the minimum over the ACDs).
DistanceFields buildTimedFields(const Regions& regions, unsigned kinds, ExtentCode eacdCode,
                                std::vector<StageTime>& stages);

// What the stages produced: voxels, regions, mean region size, mean leap per field and octant
// (PC radius, ACD edge, EACD extents), bytes per chunk group and the stage times given.
nlohmann::json preparedStatistics(const PreparedVolume& prepared, const std::vector<StageTime>& stages);

// The classification as text for the metadata: the TF's JSON, or "iso value,width,strength; ...".
std::string classificationText(const ClassifyParams& params);

}  // namespace vr
