// Which constants --caster auto weighs the casters with: --calibration FILE, else the per-user file when it was
// measured on the rendering device, else the built-in ones (render/caster_choice.h).
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/caster_calibration_file.h"

namespace vr {

struct CalibrationInUse {
    CasterCalibration constants;
    std::string source;  // "built-in" or the file's path
    std::string note;    // why the per-user file was passed over; empty when it was not
};

// $XDG_CONFIG_HOME/volrender/calibration.json, else ~/.config/volrender/calibration.json; none when neither
// variable gives an absolute folder.
std::optional<std::filesystem::path> userCalibrationPath();

// The file `explicitPath` (--calibration; empty when not given) must be a valid calibration measured on
// `deviceName`, else InputError naming it and the problem. Without a device (the CPU reference, which no file
// measures) any device's file is taken.
CalibrationInUse calibrationInUse(const std::string& explicitPath, const std::optional<std::string>& deviceName);

// Whether calibrationInUse reads a file (--calibration, or the per-user file that exists), whose device it checks
// against the rendering device's name: without one the built-in constants need no device to choose by.
bool calibrationReadsFile(const std::string& explicitPath);

// The --stats object: the source, the device it was measured on and the constants.
nlohmann::json calibrationStatistics(const CalibrationInUse& calibration);

}  // namespace vr
