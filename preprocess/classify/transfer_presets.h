// The built-in transfer functions (preprocess/classify/presets/*.json, embedded in the tools), which --tf takes by
// name (docs/ALGORITHMS.md section 2).
#pragma once
#include <string>
#include <vector>

#include "preprocess/classify/transfer_function.h"

namespace vr {

// Every built-in preset, parsed once, in name order. Each has a name, units and a description.
const std::vector<TransferFunction>& transferPresets();

// The preset of that name, ignoring case (ct-bone is CT-Bone); nullptr when there is none.
const TransferFunction* findTransferPreset(const std::string& name);

// The presets' names, comma-separated, for a message.
std::string transferPresetNames();

// One line per preset, as --list-presets prints it: the name, the range of its points and the values it makes
// visible (opacity above 0) in its units, and its description.
std::string transferPresetListing();

}  // namespace vr
