#include "io/caster_calibration_file.h"

#include <cmath>
#include <fstream>
#include <type_traits>

#include "core/errors.h"
#include "core/printable_text.h"
#include "io/atomic_file.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kFormat = "volrender caster calibration";
constexpr int kVersion = 2;  // 2 added iterationGrowth; a version 1 file has none (no growth)

// The problem with a calibration's values, or empty when there is none.
std::string problemWith(const CasterCalibration& c) {
    auto bad = [](double x) { return !(x >= 0) || !std::isfinite(x); };
    if (bad(c.rayNs)) return "rayNs must be a finite number >= 0";
    for (std::size_t i = 0; i < c.iterationNs.size(); ++i)
        if (bad(c.iterationNs[i]))
            return std::string("iterationNs.") + kCalibratedCasters[i] + " must be a finite number >= 0";
    if (bad(c.uploadNsPerByte)) return "uploadNsPerByte must be a finite number >= 0";
    if (bad(c.tie) || c.tie >= 1) return "tie must be a fraction in [0, 1)";
    if (bad(c.growth.cachedBytes)) return "iterationGrowth.cachedBytes must be a finite number >= 0";
    if (bad(c.growth.perDoubling)) return "iterationGrowth.perDoubling must be a finite number >= 0";
    if (bad(c.blocksIterationRatio)) return "blocksIterationRatio must be a finite number >= 0";
    if (c.deviceName.empty()) return "device.name must name the Vulkan device it was measured on";
    return {};
}

// Reads the JSON value at `key` of `j` as T, or says which key is missing or of the wrong type.
template <typename T>
T valueAt(const json& j, const std::string& where, const char* key) {
    const auto it = j.find(key);
    if (it == j.end()) throw InputError(where + key + " is missing");
    constexpr bool text = std::is_same_v<T, std::string>;
    if (text ? !it->is_string() : !it->is_number())
        throw InputError(where + key + (text ? " must be a string" : " must be a number"));
    return it->get<T>();
}

CasterCalibration calibrationFromJson(const json& j) {
    if (!j.is_object() || valueAt<std::string>(j, "", "format") != kFormat)
        throw InputError(std::string("not a calibration file (\"format\" must be \"") + kFormat + "\")");
    const double version = valueAt<double>(j, "", "version");
    if (version != 1 && version != kVersion)
        throw InputError("version " + j.at("version").dump() + " is not supported (1 or " + std::to_string(kVersion) +
                         ")");
    CasterCalibration c;
    c.rayNs = valueAt<double>(j, "", "rayNs");
    const json iterations = j.value("iterationNs", json::object());
    for (std::size_t i = 0; i < c.iterationNs.size(); ++i)
        c.iterationNs[i] = valueAt<double>(iterations, "iterationNs.", kCalibratedCasters[i]);
    c.uploadNsPerByte = valueAt<double>(j, "", "uploadNsPerByte");
    c.tie = valueAt<double>(j, "", "tie");
    if (version >= 2) {
        const json growth = j.value("iterationGrowth", json::object());
        c.growth.cachedBytes = valueAt<double>(growth, "iterationGrowth.", "cachedBytes");
        c.growth.perDoubling = valueAt<double>(growth, "iterationGrowth.", "perDoubling");
        if (j.contains("blocksIterationRatio")) c.blocksIterationRatio = valueAt<double>(j, "", "blocksIterationRatio");
    }
    const json device = j.value("device", json::object());
    c.deviceName = valueAt<std::string>(device, "device.", "name");
    c.driverVersion = valueAt<std::string>(device, "device.", "driverVersion");
    c.measuredAt = valueAt<std::string>(device, "device.", "measuredAt");
    if (const std::string problem = problemWith(c); !problem.empty()) throw InputError(problem);
    return c;
}

}  // namespace

json casterCalibrationJson(const CasterCalibration& c) {
    json iterations = json::object();
    for (std::size_t i = 0; i < c.iterationNs.size(); ++i) iterations[kCalibratedCasters[i]] = c.iterationNs[i];
    return {{"format", kFormat},
            {"version", kVersion},
            {"device", {{"name", c.deviceName}, {"driverVersion", c.driverVersion}, {"measuredAt", c.measuredAt}}},
            {"rayNs", c.rayNs},
            {"iterationNs", iterations},
            {"iterationGrowth", {{"cachedBytes", c.growth.cachedBytes}, {"perDoubling", c.growth.perDoubling}}},
            {"blocksIterationRatio", c.blocksIterationRatio},
            {"uploadNsPerByte", c.uploadNsPerByte},
            {"tie", c.tie}};
}

CasterCalibration readCasterCalibration(const fs::path& path) {
    std::ifstream in(path);
    if (!in) throw fileError(path.string(), fs::exists(path) ? "cannot read the calibration file" : "no such file");
    try {
        return calibrationFromJson(json::parse(in));
    } catch (const json::exception& e) {
        throw fileError(path.string(), std::string("not valid JSON: ") + printableText(e.what()));
    } catch (const InputError& e) {
        throw fileError(path.string(), printableText(e.what()));
    }
}

void writeCasterCalibration(const fs::path& path, const CasterCalibration& c) {
    if (const std::string problem = problemWith(c); !problem.empty())
        throw fileError(path.string(), "cannot write the calibration: " + problem);
    writeFileAtomically(path, [&](std::ostream& out) { out << casterCalibrationJson(c).dump(2) << "\n"; });
}

}  // namespace vr
