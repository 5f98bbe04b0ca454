#include "volrender/cmd/calibration_in_use.h"

#include <cstdlib>

#include "core/errors.h"
#include "render/caster_choice.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// An absolute folder named by the environment variable, or none (the XDG rule: relative paths are ignored).
std::optional<fs::path> absoluteFolder(const char* variable) {
    const char* value = std::getenv(variable);
    if (!value || !fs::path(value).is_absolute()) return std::nullopt;
    return fs::path(value);
}

// The calibration in `path`, refused when measured on another device than `deviceName`.
CasterCalibration readForDevice(const fs::path& path, const std::optional<std::string>& deviceName) {
    CasterCalibration c = readCasterCalibration(path);
    if (deviceName && c.deviceName != *deviceName)
        throw fileError(path.string(), "measured on '" + c.deviceName + "', not on this run's device '" +
                                           *deviceName + "' (run bench/auto_caster_bench --write-calibration on it)");
    return c;
}

// The file calibrationInUse reads: --calibration's, else the per-user file where it exists; none.
std::optional<fs::path> calibrationFile(const std::string& explicitPath) {
    if (!explicitPath.empty()) return fs::path(explicitPath);
    std::optional<fs::path> user = userCalibrationPath();
    return user && fs::exists(*user) ? user : std::nullopt;
}

}  // namespace

std::optional<fs::path> userCalibrationPath() {
    if (const auto config = absoluteFolder("XDG_CONFIG_HOME")) return *config / "volrender" / "calibration.json";
    if (const auto home = absoluteFolder("HOME")) return *home / ".config" / "volrender" / "calibration.json";
    return std::nullopt;
}

CalibrationInUse calibrationInUse(const std::string& explicitPath, const std::optional<std::string>& deviceName) {
    const std::optional<fs::path> file = calibrationFile(explicitPath);
    if (!file) return {builtInCalibration(), "built-in", ""};
    if (!explicitPath.empty()) return {readForDevice(*file, deviceName), explicitPath, ""};
    try {  // the per-user file, passed over where it does not fit this device
        return {readForDevice(*file, deviceName), file->string(), ""};
    } catch (const InputError& e) {
        return {builtInCalibration(), "built-in", std::string(e.what()) + ": using the built-in constants"};
    }
}

bool calibrationReadsFile(const std::string& explicitPath) { return calibrationFile(explicitPath).has_value(); }

nlohmann::json calibrationStatistics(const CalibrationInUse& calibration) {
    nlohmann::json stats = casterCalibrationJson(calibration.constants);
    stats.erase("format");
    stats.erase("version");
    stats["source"] = calibration.source;
    return stats;
}

}  // namespace vr
