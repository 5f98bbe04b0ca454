// volprep: prepares a volume for rendering (load -> classify -> segment -> distance fields -> prepared file).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "preprocess/cmd/summary.h"
#include "preprocess/pipeline/staged_prepare.h"
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
    std::string input, output, tf;
    double to = 0.01, ta = 3;
    std::vector<std::string> fields{"pc", "acd", "eacd"};
    std::string eacdCode{vr::extentCodeName(vr::kDefaultExtentCode)};
    bool trilinear = true, nearest = false, noNormals = false;
    std::vector<int> dims;
    std::string type;
    std::vector<double> spacing;
    bool bigEndian = false;
};

void addFlags(CLI::App& app, Flags& f) {
    app.add_option("input", f.input,
                   "volume file: .raw/.raw.gz (dims and type from the name NAME_DxDxD_TYPE or the flags), .nrrd, "
                   ".mhd/.mha, .nii/.nii.gz, .vti, .vtk, .vdb, or a DICOM series folder")
        ->required();
    app.add_option("-o,--output", f.output, "prepared file to write (written atomically)")->required();
    app.add_option("--tf", f.tf, "transfer function: ParaView preset JSON")->required();
    app.add_option("--to", f.to, "T_o: opacity (and colour) variation allowed within a region")->capture_default_str();
    app.add_option("--ta", f.ta, "T_a: normal angle allowed within a region, degrees")->capture_default_str();
    app.add_option("--fields", f.fields, "distance fields to build, comma-separated")
        ->delimiter(',')
        ->check(CLI::IsMember({"pc", "acd", "eacd"}))
        ->capture_default_str();
    app.add_option("--eacd-code", f.eacdCode,
                   "how EACD box extents are stored, rounded down: log16 (2 bytes per octant, exact to 16, cap 255), "
                   "joint8 (1 byte per octant, 6 levels per axis up to 50) or exact (3 bytes)")
        ->check(CLI::IsMember({"log16", "joint8", "exact"}))
        ->capture_default_str();
    auto* trilinear = app.add_flag("--trilinear", f.trilinear,
                                   "regions for trilinear sampling, which volrender does by default (post-"
                                   "classification: a region's interpolated scalars all classify alike); the default");
    app.add_flag("--nearest", f.nearest,
                 "regions for nearest sampling only (volrender --nearest): larger regions, faster to build")
        ->excludes(trilinear);
    app.add_flag("--no-normals", f.noNormals,
                 "regions ignore the normals (T_a unused): leaping casters then render unshaded only");
    auto* raw = app.add_option_group("raw input", "for headerless raw files whose name does not say it");
    raw->add_option("--dims", f.dims, "grid size, e.g. 256x256x128")->delimiter('x')->expected(3);
    raw->add_option("--type", f.type, "voxel type: uint8, int16, uint16 or float32");
    raw->add_option("--spacing", f.spacing, "voxel size x,y,z")->delimiter(',')->expected(3);
    raw->add_flag("--big-endian", f.bigEndian, "multi-byte voxels are big-endian");
}

// Checks that need no data, so that a bad run fails at once rather than after the expensive stages.
void checkBeforeRunning(const Flags& f) {
    if (!(f.to >= 0) || !std::isfinite(f.to))
        throw vr::InputError("--to must be a finite number >= 0, got " + std::to_string(f.to));
    if (!(f.ta >= 0) || !std::isfinite(f.ta))
        throw vr::InputError("--ta must be a finite number >= 0 (degrees), got " + std::to_string(f.ta));
    fs::path out(f.output);
    fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(folder))
        throw vr::fileError(f.output, "cannot write: folder " + folder.string() + " does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        throw vr::fileError(f.output, "cannot write: folder " + folder.string() + " is not writable");
    if (fs::is_directory(out)) throw vr::fileError(f.output, "cannot write: it is a folder");
}

vr::RawOptions rawOptionsFrom(const Flags& f) {
    vr::RawOptions raw;
    if (!f.dims.empty()) raw.dims = vr::Vec3i{f.dims[0], f.dims[1], f.dims[2]};
    if (!f.type.empty()) raw.type = vr::parseScalarType(f.type);
    if (!f.spacing.empty()) raw.spacing = vr::Vec3d{f.spacing[0], f.spacing[1], f.spacing[2]};
    raw.bigEndian = f.bigEndian;
    return raw;
}

vr::PrepareOptions optionsFrom(const Flags& f) {
    vr::PrepareOptions o;
    o.classify.transferFunction = vr::loadTransferFunction(f.tf);
    o.classify.normals = !f.noNormals;
    o.segmentation = {f.to, f.ta, !f.noNormals, !f.nearest};
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
        const vr::RawOptions raw = rawOptionsFrom(flags);
        const vr::PrepareOptions options = optionsFrom(flags);  // a bad transfer function fails before the load
        // Segmented once: the classified volume's memory goes to the fields.
        vr::StagedPreparation staged =
            vr::StagedPreparation::load(flags.input, raw, vr::ClassifiedOnceSegmented::Free);
        staged.prepare(options);
        staged.write(flags.output);
        vr::printSummary(stdout, flags.output, staged.withStatistics(), staged.stageTimes());
        return 0;
    });
}
