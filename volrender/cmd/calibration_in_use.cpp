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

}  // namespace

std::optional<fs::path> userCalibrationPath() {
    if (const auto config = absoluteFolder("XDG_CONFIG_HOME")) return *config / "volrender" / "calibration.json";
    if (const auto home = absoluteFolder("HOME")) return *home / ".config" / "volrender" / "calibration.json";
    return std::nullopt;
}

CalibrationInUse calibrationInUse(const std::string& explicitPath, const std::optional<std::string>& deviceName) {
    if (!explicitPath.empty()) return {readForDevice(explicitPath, deviceName), explicitPath, ""};
    const std::optional<fs::path> user = userCalibrationPath();
    if (!user || !fs::exists(*user)) return {builtInCalibration(), "built-in", ""};
    try {
        return {readForDevice(*user, deviceName), user->string(), ""};
    } catch (const InputError& e) {
        return {builtInCalibration(), "built-in", std::string(e.what()) + ": using the built-in constants"};
    }
}

bool calibrationReadsFile(const std::string& explicitPath) {
    const std::optional<fs::path> user = userCalibrationPath();
    return !explicitPath.empty() || (user && fs::exists(*user));
}

nlohmann::json calibrationStatistics(const CalibrationInUse& calibration) {
    nlohmann::json stats = casterCalibrationJson(calibration.constants);
    stats.erase("format");
    stats.erase("version");
    stats["source"] = calibration.source;
    return stats;
}

}  // namespace vr
