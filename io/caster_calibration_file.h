// The constants of --caster auto's cost model (render/caster_choice.h) as measured on one device, and their JSON
// file: bench/auto_caster_bench --write-calibration writes it, volrender --calibration reads it.
#pragma once
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace vr {

// The casters whose loop iteration the file prices, in the order of render/render_settings.h's Caster.
constexpr std::array<const char*, 4> kCalibratedCasters{"primitive", "pc", "acd", "eacd"};

struct CasterCalibration {
    double rayNs = 0;                     // device time of a ray, whatever its iterations
    std::array<double, 4> iterationNs{};  // device time of one loop iteration, per caster (kCalibratedCasters)
    double uploadNsPerByte = 0;           // wall time of uploading one byte of a field
    double tie = 0;                       // estimates within this fraction of the cheapest are a tie
    // Where and when it was measured: the Vulkan device name (the one volrender matches), its driver version and
    // the time in ISO 8601 UTC.
    std::string deviceName, driverVersion, measuredAt;
    bool operator==(const CasterCalibration&) const = default;
};

nlohmann::json casterCalibrationJson(const CasterCalibration& calibration);

// Throws InputError naming `path` and the problem: unreadable, not JSON, not a calibration, a constant missing,
// negative or not a number, a tie outside [0, 1), or the device's name missing.
CasterCalibration readCasterCalibration(const std::filesystem::path& path);

// Writes atomically (io/atomic_file.h) after the checks the reader makes, so that no file is written that
// volrender would refuse.
void writeCasterCalibration(const std::filesystem::path& path, const CasterCalibration& calibration);

}  // namespace vr
