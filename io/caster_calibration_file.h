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

// How an iteration's time grows once the scalars outgrow the caches the casters sample them through: by
// perDoubling of itself per doubling of the scalars' device bytes beyond cachedBytes (render/caster_choice.h).
// Zero: every volume priced alike, as a file of version 1 prices it.
struct IterationGrowth {
    double cachedBytes = 0;
    double perDoubling = 0;
    bool operator==(const IterationGrowth&) const = default;
};

struct CasterCalibration {
    double rayNs = 0;                     // device time of a ray, whatever its iterations
    std::array<double, 4> iterationNs{};  // device time of one loop iteration, per caster (kCalibratedCasters)
    double uploadNsPerByte = 0;           // wall time of uploading one byte of a field
    double tie = 0;                       // estimates within this fraction of the cheapest are a tie
    // Where and when it was measured: the Vulkan device name (the one volrender matches), its driver version and
    // the time in ISO 8601 UTC.
    std::string deviceName, driverVersion, measuredAt;
    IterationGrowth growth;  // of every caster's iteration time with the volume's bytes
    // A MIP iteration of the blocks caster over one of the primitive caster, whole renders' device time per
    // iteration (the ray's own cost included): a block lookup and, on a SIMD device, lanes that wait for the rays
    // still sampling. 0: not measured, the built-in value (render/caster_choice.h) stands.
    double blocksIterationRatio = 0;
    bool operator==(const CasterCalibration&) const = default;
};

nlohmann::json casterCalibrationJson(const CasterCalibration& calibration);

// Reads version 2 (with iterationGrowth; blocksIterationRatio optional) and version 1 (without: no growth).
// Throws InputError naming `path` and the problem: unreadable, not JSON, not a calibration, another version, a
// constant missing, negative or not a number, a tie outside [0, 1), or the device's name missing.
CasterCalibration readCasterCalibration(const std::filesystem::path& path);

// Writes version 2 atomically (io/atomic_file.h) after the checks the reader makes, so that no file is written that
// volrender would refuse.
void writeCasterCalibration(const std::filesystem::path& path, const CasterCalibration& calibration);

}  // namespace vr
