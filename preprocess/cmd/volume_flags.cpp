#include "preprocess/cmd/volume_flags.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/errors.h"
#include "core/number_text.h"
#include "preprocess/classify/transfer_presets.h"
#include "preprocess/load/load_labels.h"

namespace vr {

CLI::Option_group* addTransferFlags(CLI::App& app, TransferChoice& choice) {
    auto* group = app.add_option_group("transfer function", "--tf, or --window and --level, or all three");
    group->add_option("--tf", choice.tf,
                      "a built-in preset's name (CT-Bone, MR-Default, ...: see --list-presets) or a ParaView preset "
                      "JSON file");
    auto* window = group->add_option_function<double>(
        "--window", [&choice](double w) { choice.window = w; },
        "width of a linear opacity ramp, in the volume's units (HU for a CT): opacity 0 at level - window/2 to 1 at "
        "level + window/2; grey, or coloured by --tf. volrender --blend mip, minip and average show it opaque: a "
        "grey window");
    auto* level = group->add_option_function<double>(
        "--level", [&choice](double l) { choice.level = l; }, "the value at the middle of --window's ramp");
    window->needs(level);
    level->needs(window);
    app.add_flag_callback(
        "--list-presets",
        [] {
            std::fputs(transferPresetListing().c_str(), stdout);
            throw CLI::Success();  // a listing, like --help: no run
        },
        "list the built-in transfer-function presets (name, values, units, what they show) and exit");
    return group;
}

CLI::Option_group* addVolumeFlags(CLI::App& app, VolumeFlags& f) {
    CLI::Option_group* transfer = addTransferFlags(app, f.transfer);
    app.add_option("--to", f.to, "T_o: opacity (and colour) variation allowed within a region")
        ->capture_default_str()
        ->each([&f](const std::string&) { f.toGiven = true; });
    app.add_option("--ta", f.ta, "T_a: normal angle allowed within a region, degrees")
        ->capture_default_str()
        ->each([&f](const std::string&) { f.taGiven = true; });
    auto* raw = app.add_option_group("raw input", "for headerless raw files whose name does not say it");
    raw->add_option("--dims", f.dims, "grid size, e.g. 256x256x128")->delimiter('x')->expected(3);
    raw->add_option("--type", f.type, "voxel type: uint8, int16, uint16 or float32");
    raw->add_option("--spacing", f.spacing, "voxel size x,y,z")->delimiter(',')->expected(3);
    raw->add_flag("--big-endian", f.bigEndian, "multi-byte voxels are big-endian");
    app.add_option("--series", f.series,
                   "DICOM folder holding several series: the SeriesInstanceUID to read (the error lists them)");
    app.add_option("--labels", f.labels,
                   "a label map on the volume's grid (any format the volume may be in), integer labels 0..65535: "
                   "each label shows in its own colour and opacity beside the transfer function");
    app.add_option("--label-colors", f.labelColours,
                   "the labels' colours: a 3D Slicer colour table ('index name r g b a' a line, 0..255; a: opacity "
                   "per voxel step); default: label 0 clear, the others a ten-colour palette at opacity 0.8");
    return transfer;
}

void checkThresholds(const VolumeFlags& f, bool normals) {
    if (!(f.to >= 0) || !std::isfinite(f.to))
        throw InputError("--to must be a finite number >= 0, got " + numberText(f.to));
    if (!(f.ta >= 0) || !std::isfinite(f.ta))
        throw InputError("--ta must be a finite number >= 0 (degrees), got " + numberText(f.ta));
    if (f.taGiven && f.ta > 0 && !normals)  // --ta 0 asks for nothing: thresholds 0 read as such
        throw InputError("--ta " + numberText(f.ta) + ": the regions are made without normals (unshaded), so no "
                         "normal angle bounds them");
}

RawOptions rawOptionsFrom(const VolumeFlags& f) {
    RawOptions raw;
    if (!f.dims.empty()) raw.dims = Vec3i{f.dims[0], f.dims[1], f.dims[2]};
    if (!f.type.empty()) raw.type = parseScalarType(f.type);
    if (!f.spacing.empty()) raw.spacing = Vec3d{f.spacing[0], f.spacing[1], f.spacing[2]};
    raw.bigEndian = f.bigEndian;
    raw.series = f.series;
    return raw;
}

std::optional<LabelColourTable> checkLabelFlags(const VolumeFlags& f) {
    if (!f.labelColours.empty() && f.labels.empty())
        throw InputError("--label-colors " + f.labelColours + ": a colour table is for a label map: it needs --labels");
    if (!f.labels.empty() && !std::filesystem::exists(f.labels))
        throw InputError("--labels " + f.labels + ": no such file");
    if (f.labelColours.empty()) return std::nullopt;
    return readLabelColourTable(f.labelColours, "--label-colors");
}

void attachLabels(const VolumeFlags& f, const std::optional<LabelColourTable>& table, StagedPreparation& staged) {
    if (f.labels.empty()) return;
    LabelMap map = loadLabelMap(f.labels, staged.volume().grid, "--labels");
    map.rgba = labelColours(map, table ? &*table : nullptr, "--label-colors");
    map.colourTable = table ? table->source : std::string();
    staged.setLabels(std::move(map));
}

PrepareOptions prepareOptionsFrom(const VolumeFlags& f, bool nearest, bool noNormals) {
    PrepareOptions o;
    o.classify.transferFunction = chooseTransferFunction(f.transfer);
    o.classify.normals = !noNormals;
    o.segmentation = {f.to, f.ta, !noNormals, !nearest};
    return o;
}

}  // namespace vr
