// What volsweep is asked to do: one dataset, a grid of thresholds, the casters, the views and the outputs.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "preprocess/classify/transfer_choice.h"
#include "preprocess/load/load_volume.h"
#include "render/render_settings.h"

namespace vr {

struct SweepOptions {
    std::filesystem::path input;
    std::string dataset;                 // name in the CSV and report; empty: the input's name without extensions
    RawOptions raw;
    TransferChoice transfer;             // --tf (a preset or a file), --window, --level
    std::vector<double> opacityThresholds{0, 0.005, 0.01, 0.02, 0.05, 0.1};  // T_o
    std::vector<double> angleThresholds{0, 1, 3, 10, 20};                    // T_a, degrees
    std::vector<Caster> casters{Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD};
    int downsample = 1;                  // > 1: sweep the volume box-averaged over blocks of this many voxels^3
    int views = 8;                       // azimuths 360 i / views ...
    std::vector<double> elevations{0};   // ... at each of these elevations
    int width = 512, height = 512;
    double stepVoxels = 0.5;
    bool shading = true;
    bool trilinear = true;
    // Every caster's rays jittered (shaders/jitter.h), each image compared with the unjittered reference: the
    // dataset's rows are named NAME+jitter, apart from an unjittered sweep's.
    bool jitter = false;
    int device = -1;                     // Vulkan device index; -1: the default choice
    std::filesystem::path outDir;
    bool resume = false;                 // skip settings already in OUTDIR/sweep.csv
    std::filesystem::path peersDir;      // a folder holding peers.json (scripts/peers.sh); empty: none

    // Throws InputError for an empty grid, negative or non-finite thresholds, an angle above 0 without shading, no
    // primitive caster, bad sizes.
    void validate() const;
    // The dataset name used (dataset, else derived from input; "+jitter" appended with jitter).
    std::string datasetName() const;
    // What a dataset's rows share beside their size and views, as sweep.csv's render column writes it (no commas):
    // the transfer function, the sampling, the shading, the step, the elevations and the downsampling.
    std::string renderSettings() const;
};

}  // namespace vr
