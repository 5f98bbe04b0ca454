#include "sweep/sweep_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "sweep/metrics/ssim.h"

namespace vr {

void SweepOptions::validate() const {
    if (input.empty()) throw InputError("no input volume given");
    if (transfer.empty())
        throw InputError("no transfer function given: --tf PRESET or --tf FILE.json, or --window W --level L");
    if (outDir.empty()) throw InputError("no output folder given: -o OUTDIR");
    if (std::filesystem::exists(outDir) && !std::filesystem::is_directory(outDir))
        throw InputError("-o " + outDir.string() + ": a file, not a folder (the sweep writes sweep.csv, report.md, "
                         "plots/, strips/ and images/ into it)");
    auto checkGrid = [](const std::vector<double>& grid, const char* flag) {
        if (grid.empty()) throw InputError(std::string(flag) + ": give at least one threshold");
        for (double t : grid)
            if (!std::isfinite(t) || t < 0)
                throw InputError(std::string(flag) + ": thresholds must be finite and >= 0");
    };
    checkGrid(opacityThresholds, "--to");
    checkGrid(angleThresholds, "--ta");
    if (!shading && std::any_of(angleThresholds.begin(), angleThresholds.end(), [](double t) { return t > 0; }))
        throw InputError("--ta: an unshaded sweep (--no-shading) makes its regions without normals, which no angle "
                         "bounds: its only T_a is 0");
    if (std::find(casters.begin(), casters.end(), Caster::Primitive) == casters.end())
        throw InputError("--casters must include primitive: the other casters' times are given relative to it");
    if (downsample < 1 || downsample > 16) throw InputError("--downsample must be in 1..16");
    if (views < 1 || views > 360) throw InputError("--views must be in 1..360");
    if (elevations.empty()) throw InputError("--elevations: give at least one elevation");
    for (double e : elevations)
        if (!std::isfinite(e)) throw InputError("--elevations must be finite");
    if (width < kSsimWindow || height < kSsimWindow || width > 8192 || height > 8192)
        throw InputError("--size: width and height must be in 11..8192 (SSIM needs an 11x11 window)");
    if (!(stepVoxels > 0) || !std::isfinite(stepVoxels)) throw InputError("--step must be a positive number");
    if (!peersDir.empty() && !std::filesystem::is_regular_file(peersDir / "peers.json"))
        throw InputError("--peers " + peersDir.string() + ": no peers.json there (run scripts/peers.sh)");
    const std::string name = datasetName();
    if (name.empty() || name.find_first_of(",\n\"") != std::string::npos)
        throw InputError("dataset name '" + name + "' must be non-empty, without commas or quotes (use --name)");
}

std::string SweepOptions::datasetName() const {
    std::string name = dataset;
    if (name.empty()) {
        name = input.filename().string();
        for (const std::string ext : {".gz", ".raw", ".nii", ".nrrd", ".nhdr", ".mhd", ".mha", ".vti", ".vtk", ".vdb"})
            if (name.size() > ext.size() && name.ends_with(ext)) name.resize(name.size() - ext.size());
    }
    return jitter ? name + "+jitter" : name;
}

std::string SweepOptions::renderSettings() const {
    std::ostringstream s;
    if (!transfer.tf.empty()) s << "tf=" << std::filesystem::path(transfer.tf).filename().string() << ' ';
    if (transfer.window) s << "window=" << *transfer.window << " level=" << *transfer.level << ' ';
    s << (trilinear ? "trilinear" : "nearest") << ' ' << (shading ? "shaded" : "unshaded") << " step=" << stepVoxels
      << " elevations=";
    for (std::size_t i = 0; i < elevations.size(); ++i) s << (i ? ";" : "") << elevations[i];
    if (downsample > 1) s << " downsample=" << downsample;
    std::string text = s.str();
    std::replace_if(text.begin(), text.end(), [](char c) { return c == ',' || c == '\n' || c == '\r'; }, ';');
    return text;
}

}  // namespace vr
