// volsweep: the threshold sweep of docs/BENCH.md "Error against run time". One dataset per run: load and classify
// once, then per (T_o, T_a) segment, build the fields and render every caster at every view on the Vulkan device,
// comparing with the primitive caster at thresholds 0; appends OUTDIR/sweep.csv and rewrites OUTDIR/report.md
// (all datasets of the CSV), the plots and the image strips.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "tools/tool_main.h"
#include "core/errors.h"
#include "preprocess/cmd/volume_flags.h"
#include "sweep/report.h"
#include "sweep/run_sweep.h"

namespace {

constexpr vr::ToolText kText{
    "volsweep",
    "Sweeps the homogeneity thresholds (T_o, T_a) of one volume: per setting the preprocessing time, every "
    "caster's render time on the Vulkan device and its error against the primitive caster at thresholds 0 "
    "(RMSE, PSNR, max error, SSIM, % pixels off by > 1/255, % with CIEDE2000 > 2.3). Appends OUTDIR/sweep.csv "
    "and rewrites OUTDIR/report.md with plots and image strips.",
    "Exit status: 0 done, 1 bad input or device failure, 2 bad command line."};

struct Flags {
    std::string input, name, size = "512x512", type, outDir, peers;
    std::vector<double> spacing, to{0, 0.005, 0.01, 0.02, 0.05, 0.1}, ta{0, 1, 3, 10, 20}, elevations{0};
    std::vector<int> dims;
    std::vector<std::string> casters{"primitive", "pc", "acd", "eacd"};
    vr::TransferChoice transfer;
    int views = 8, device = -1, downsample = 1;
    double step = 0.5;
    bool noShading = false, nearest = false, jitter = false, resume = false, reportOnly = false;
    bool taGiven = false;  // --ta on the command line
};

void addFlags(CLI::App& app, Flags& f) {
    app.add_option("input", f.input, "volume file (raw .raw[.gz] named NAME_XxYxZ_TYPE, NRRD, MetaImage, NIfTI, ...)");
    vr::addTransferFlags(app, f.transfer);
    app.add_option("--spacing", f.spacing, "voxel size x,y,z for raw volumes")->delimiter(',')->expected(3);
    app.add_option("--dims", f.dims, "grid size XxYxZ for raw volumes (default: from the name)")
        ->delimiter('x')->expected(3);
    app.add_option("--type", f.type, "voxel type of raw volumes: uint8, int16, uint16, float32");
    app.add_option("--name", f.name, "dataset name in the CSV and report (default: the file name)");
    app.add_option("--to", f.to, "opacity thresholds T_o")->delimiter(',')->capture_default_str();
    app.add_option("--ta", f.ta, "normal angle thresholds T_a, degrees (--no-shading: 0 alone)")
        ->delimiter(',')
        ->capture_default_str()
        ->each([&f](const std::string&) { f.taGiven = true; });
    app.add_option("--casters", f.casters, "casters (primitive is required: times are relative to it)")
        ->delimiter(',')->check(CLI::IsMember({"primitive", "pc", "acd", "eacd"}))->capture_default_str();
    app.add_option("--downsample", f.downsample, "average blocks of NxNxN voxels first (a smaller volume, faster "
                                                 "sweeps)")->capture_default_str();
    app.add_option("--views", f.views, "azimuths per elevation, 360/N degrees apart")->capture_default_str();
    app.add_option("--elevations", f.elevations, "camera elevations, degrees")->delimiter(',')
        ->capture_default_str();
    app.add_option("--size", f.size, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--step", f.step, "sampling step in voxels of the smallest spacing")->capture_default_str();
    app.add_flag("--no-shading", f.noShading, "emission-absorption only: regions without normals, T_a 0 alone");
    app.add_flag("--nearest", f.nearest,
                 "nearest sampling, regions made for it (default: trilinear, the scalar interpolated then classified)");
    app.add_flag("--jitter", f.jitter, "jitter every caster's rays (volrender --jitter), each image's error still "
                                       "against the unjittered primitive reference; rows named NAME+jitter");
    app.add_option("--device", f.device, "Vulkan device index (default: first discrete GPU, else the first)");
    app.add_option("-o,--out", f.outDir, "output folder: sweep.csv, report.md, plots/, strips/, images/");
    app.add_flag("--resume", f.resume, "skip the settings whose rows are already in OUTDIR/sweep.csv");
    app.add_option("--peers", f.peers, "folder with peers.json from scripts/peers.sh, joined into the report");
    app.add_flag("--report-only", f.reportOnly, "only rewrite the report, plots and strips from OUTDIR/sweep.csv");
}

vr::SweepOptions options(const Flags& f) {
    vr::SweepOptions o;
    o.input = f.input;
    o.transfer = f.transfer;
    o.dataset = f.name;
    if (!f.spacing.empty()) o.raw.spacing = vr::Vec3d{f.spacing[0], f.spacing[1], f.spacing[2]};
    if (!f.dims.empty()) o.raw.dims = vr::Vec3i{f.dims[0], f.dims[1], f.dims[2]};
    if (!f.type.empty()) o.raw.type = vr::parseScalarType(f.type);
    o.opacityThresholds = f.to;
    // Unshaded regions have no normals to bound: the default grid becomes T_a 0 alone, a given one is checked.
    o.angleThresholds = f.noShading && !f.taGiven ? std::vector<double>{0} : f.ta;
    o.casters.clear();
    for (const std::string& c : f.casters) o.casters.push_back(vr::parseCaster(c));
    o.downsample = f.downsample;
    o.views = f.views;
    o.elevations = f.elevations;
    char extra = 0;
    if (std::sscanf(f.size.c_str(), "%dx%d%c", &o.width, &o.height, &extra) != 2)
        throw vr::InputError("--size '" + f.size + "': expected WIDTHxHEIGHT, e.g. 256x256");
    o.stepVoxels = f.step;
    o.shading = !f.noShading;
    o.trilinear = !f.nearest;
    o.jitter = f.jitter;
    o.device = f.device;
    o.outDir = f.outDir;
    o.resume = f.resume;
    o.peersDir = f.peers;
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    return vr::runTool<Flags>(kText, argc, argv, addFlags, [](const Flags& flags) {
        if (flags.outDir.empty()) throw vr::InputError("no output folder given: -o OUTDIR");
        if (!flags.reportOnly) {
            if (flags.input.empty()) throw vr::InputError("no input volume given (see --help)");
            const int settings = vr::runSweep(options(flags));
            std::fprintf(stderr, "volsweep: %d settings run\n", settings);
        }
        std::printf("%s\n", vr::writeReport(flags.outDir).c_str());
        return 0;
    });
}
