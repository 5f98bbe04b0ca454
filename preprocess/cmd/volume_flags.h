// The flags that say how to read and prepare a volume, shared by volprep and by volrender's one-command path:
// the transfer function (volsweep's too), the thresholds and the raw-file description.
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "preprocess/classify/label_colours.h"
#include "preprocess/classify/transfer_choice.h"
#include "preprocess/pipeline/staged_prepare.h"

namespace vr {

struct VolumeFlags {
    TransferChoice transfer;
    double to = 0.01, ta = 3;
    bool toGiven = false, taGiven = false;  // --to, --ta on the command line
    std::vector<int> dims;
    std::string type;
    std::vector<double> spacing;
    bool bigEndian = false;
    std::string series;  // a DICOM folder's series
    std::string labels, labelColours;  // --labels LABELS, --label-colors TABLE
};

// Adds the transfer-function group (--tf, --window, --level) and --list-presets, which prints the built-in presets
// and exits; returns the group. volsweep shares them.
CLI::Option_group* addTransferFlags(CLI::App& app, TransferChoice& choice);

// Adds the transfer-function flags, --to, --ta, the raw group (--dims, --type, --spacing, --big-endian), --series
// and the label map's --labels and --label-colors; returns the transfer-function group.
CLI::Option_group* addVolumeFlags(CLI::App& app, VolumeFlags& flags);

// Throws InputError naming --to or --ta when a threshold is negative or not finite, and naming --ta when an angle
// above 0 is given for regions made without normals (`normals` false), which it would not change.
void checkThresholds(const VolumeFlags& flags, bool normals);

RawOptions rawOptionsFrom(const VolumeFlags& flags);

// Checks the label flags before any volume is read: --label-colors needs --labels, the label map must exist and
// the colour table must read. Returns the table (none for the default palette). Throws InputError naming the flag.
std::optional<LabelColourTable> checkLabelFlags(const VolumeFlags& flags);
// With --labels: loads the label map (on the volume's grid), gives it the classes of `table` (the default palette
// without one) and attaches it to `staged`. Throws InputError naming --labels or --label-colors.
void attachLabels(const VolumeFlags& flags, const std::optional<LabelColourTable>& table, StagedPreparation& staged);

// The transfer function (chosen: a bad one fails here, before any volume is read) and the thresholds; regions for
// trilinear sampling unless `nearest`, with normals unless `noNormals`. Fields and EACD code as PrepareOptions'.
PrepareOptions prepareOptionsFrom(const VolumeFlags& flags, bool nearest, bool noNormals);

}  // namespace vr
