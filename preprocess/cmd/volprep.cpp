// volprep: prepares a volume for rendering (load -> classify -> segment -> distance fields -> prepared file).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "core/lower_case.h"
#include "preprocess/cmd/summary.h"
#include "preprocess/cmd/volume_flags.h"
#include "preprocess/load/load_volume.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "tools/progress.h"
#include "tools/tool_main.h"

namespace {

constexpr vr::ToolText kText{
    "volprep",
    "Prepares a volume for volrender: classifies it with a transfer function, segments it into "
    "homogeneous regions (thresholds T_o, T_a) and builds the distance fields (PC, ACD, EACD) that let rays "
    "leap through them. Prints statistics and stage times.",
    "Exit status: 0 done, 1 bad input (file, transfer function, thresholds), 2 bad command line."};

namespace fs = std::filesystem;

struct Flags {
    std::string input, output;
    vr::VolumeFlags volume;
    std::vector<std::string> fields{"pc", "acd", "eacd"};
    std::string eacdCode{vr::extentCodeName(vr::kDefaultExtentCode)};
    bool eacdCodeGiven = false;
    bool trilinear = true, nearest = false, noNormals = false, quiet = false;
};

void addFlags(CLI::App& app, Flags& f) {
    app.add_option("input", f.input,
                   "volume file: .raw/.raw.gz (dims and type from the name NAME_DxDxD_TYPE or the flags), .nrrd, "
                   ".mhd/.mha, .nii/.nii.gz, .vti, .vtk, .vdb, or a DICOM series folder")
        ->required();
    app.add_option("-o,--output", f.output, "prepared file to write (written atomically)")->required();
    vr::addVolumeFlags(app, f.volume)->require_option(1, 0);
    app.add_option("--fields", f.fields, "distance fields to build, comma-separated")
        ->delimiter(',')
        ->check(CLI::IsMember({"pc", "acd", "eacd"}))
        ->capture_default_str();
    app.add_option("--eacd-code", f.eacdCode,
                   "how EACD box extents are stored, rounded down: log16 (2 bytes per octant, exact to 16, cap 255), "
                   "joint8 (1 byte per octant, 6 levels per axis up to 50) or exact (3 bytes)")
        ->check(CLI::IsMember({"log16", "joint8", "exact"}))
        ->capture_default_str()
        ->each([&f](const std::string&) { f.eacdCodeGiven = true; });
    auto* trilinear = app.add_flag("--trilinear", f.trilinear,
                                   "regions for trilinear sampling, which volrender does by default (post-"
                                   "classification: a region's interpolated scalars all classify alike); the default");
    app.add_flag("--nearest", f.nearest,
                 "regions for nearest sampling only (volrender --nearest): larger regions, faster to build")
        ->excludes(trilinear);
    app.add_flag("--no-normals", f.noNormals,
                 "regions ignore the normals (T_a unused): leaping casters then render unshaded only");
    app.add_flag("-q,--quiet", f.quiet, "no progress bars and no summary: errors only");
}

// Checks that need no data, so that a bad run fails at once rather than after the expensive stages.
void checkBeforeRunning(const Flags& f) {
    vr::checkThresholds(f.volume, !f.noNormals);
    if (f.eacdCodeGiven && std::find(f.fields.begin(), f.fields.end(), "eacd") == f.fields.end())
        throw vr::InputError("--eacd-code " + f.eacdCode + " stores the EACD field, which --fields leaves out");
    fs::path out(f.output);
    fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(folder))
        throw vr::fileError(f.output, "cannot write: folder " + folder.string() + " does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        throw vr::fileError(f.output, "cannot write: folder " + folder.string() + " is not writable");
    if (fs::is_directory(out)) throw vr::fileError(f.output, "cannot write: it is a folder");
    // A prepared file under a volume's or an image's name would be taken for one (and could replace the source).
    if (vr::isVolumeFileName(out))
        throw vr::fileError(f.output, "a volume file's name: volprep writes a prepared file (e.g. NAME.vprep), "
                                      "which only volrender reads");
    const std::string extension = vr::lowerCase(out.extension().string());
    for (const char* image : {".png", ".exr", ".gif", ".mp4", ".jpg", ".jpeg", ".tif", ".tiff"})
        if (extension == image)
            throw vr::fileError(f.output, "an image's name: volprep writes a prepared file (e.g. NAME.vprep); "
                                          "volrender renders it to an image");
}

vr::PrepareOptions optionsFrom(const Flags& f) {
    vr::PrepareOptions o = vr::prepareOptionsFrom(f.volume, f.nearest, f.noNormals);
    o.fields = 0;
    for (const std::string& name : f.fields)
        o.fields |= name == "pc" ? vr::kFieldPC : name == "acd" ? vr::kFieldACD : vr::kFieldEACD;
    o.eacdCode = vr::parseExtentCode(f.eacdCode, "--eacd-code");
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    return vr::runTool<Flags>(kText, argc, argv, addFlags, [](const Flags& flags) {
        checkBeforeRunning(flags);
        if (flags.quiet) vr::ProgressBar::silenceAll();
        const vr::RawOptions raw = vr::rawOptionsFrom(flags.volume);
        const vr::PrepareOptions options = optionsFrom(flags);  // a bad transfer function fails before the load
        const auto labelColours = vr::checkLabelFlags(flags.volume);  // and a bad colour table
        vr::StagedPreparation staged = vr::StagedPreparation::load(flags.input, raw);
        if (!flags.quiet)
            for (const std::string& note : staged.volume().notes)
                std::fprintf(stderr, "volprep: %s: %s\n", flags.input.c_str(), note.c_str());
        vr::attachLabels(flags.volume, labelColours, staged);
        staged.prepare(options);
        staged.write(flags.output);
        if (!flags.quiet) vr::printSummary(stdout, flags.output, staged.withStatistics(), staged.stageTimes());
        return 0;
    });
}
