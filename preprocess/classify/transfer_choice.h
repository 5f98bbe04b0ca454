// The transfer function that the tools' flags ask for (docs/ALGORITHMS.md section 2): --tf, a built-in preset's
// name or a ParaView preset JSON file, and --window with --level, a linear opacity ramp. volprep, volrender and
// volsweep share these flags, so the messages name them.
#pragma once
#include <optional>
#include <string>

#include "preprocess/classify/transfer_function.h"

namespace vr {

struct TransferChoice {
    std::string tf;                       // --tf: a preset's name (see transferPresets()) or a file; empty: none
    std::optional<double> window, level;  // --window and --level, in the volume's scalar units: both or neither
    bool empty() const { return tf.empty() && !window && !level; }
};

// The transfer function of --tf, a preset's name before a file's (write ./NAME for a file named like a preset).
// Throws InputError naming --tf and listing the presets when it is neither, or naming the file when it is bad.
TransferFunction namedTransferFunction(const std::string& presetOrFile);

// The window/level ramp: opacity 0 up to level - window/2, rising linearly to 1 at level + window/2 and 1 above;
// the colours of `colours` where given (its colour points and colour space: a preset keeps its colours at its
// values), else grey from black to white over the same values.
TransferFunction windowLevelTransferFunction(double window, double level, const TransferFunction* colours);

// --tf alone: its transfer function; --window and --level: their ramp, with --tf's colours when --tf is given.
// Throws InputError naming the flag: none of them given, --window or --level alone, a window not a finite number
// above 0, a level not finite, a window too narrow to make a ramp at that level, or a bad --tf.
TransferFunction chooseTransferFunction(const TransferChoice& choice);

}  // namespace vr
