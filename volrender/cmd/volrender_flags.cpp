#include "volrender/cmd/volrender_flags.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "core/errors.h"
#include "io/prepared_file.h"
#include "render/render_checks.h"
#include "volrender/cmd/stereo_output.h"
#include "volrender/cmd/view_output.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

void checkWritable(const std::string& path, const char* flag) {
    const fs::path out(path);
    const fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    if (!fs::is_directory(folder))
        throw fileError(path, std::string("cannot write ") + flag + ": folder " + folder.string() +
                              " does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        throw fileError(path, std::string("cannot write ") + flag + ": folder " + folder.string() +
                              " is not writable");
    if (fs::is_directory(out)) throw fileError(path, std::string("cannot write ") + flag + ": it is a folder");
}

// No output at the path of another output or of an input: it would write over the other file (the source volume
// too: --stats VOLUME replaced it), or the other file over it. -o and --heatmap are compared by every file they write:
// an orbit's numbered frames and a pair's eyes (-o x.png --views 2 --stats x_000.png wrote the JSON over a frame).
void checkDistinctFiles(const VolrenderFlags& f) {
    struct Named {
        const char* flag;
        const std::string& path;
        bool output;
        bool frames;  // written as an orbit's views or a pair's eyes
    };
    const Named named[] = {{"the input", f.input, false, false},
                           {"--labels", f.volume.labels, false, false},
                           {"--label-colors", f.volume.labelColours, false, false},
                           {"--calibration", f.calibration, false, false},
                           {"-o", f.output, true, true},
                           {"--heatmap", f.heatmap, true, true},
                           {"--stats", f.stats, true, false}};
    const auto where = [](const std::string& path) {
        std::error_code ec;
        const fs::path p = fs::weakly_canonical(path, ec);
        return ec ? fs::path(path).lexically_normal() : p;
    };
    std::map<fs::path, const Named*> seen;  // each file by where it is, with the flag that named it first
    for (const Named& b : named) {
        if (b.path.empty()) continue;
        for (const std::string& file : b.frames ? frameFiles(b.path, f.views, layoutOf(f)) : std::vector{b.path}) {
            const auto [it, fresh] = seen.emplace(where(file), &b);
            const Named& a = *it->second;
            if (fresh || !(a.output || b.output)) continue;
            std::string written;  // the flag whose orbit or pair made the name, if one did
            for (const Named* n : {&a, &b})
                if (written.empty() && where(n->path) != it->first)
                    written = " (" + std::string(n->flag) + " " + n->path + " writes it, a view of the orbit or an eye)";
            throw InputError(std::string(a.flag) + " and " + b.flag + " name the same file, " + file + written +
                             ": " + (a.output ? "one would write over the other"  // inputs come first
                                              : std::string(b.flag) + " would write over " + a.flag));
        }
    }
}

// The outputs' formats, and --fps only where a movie is written.
void checkMovieFlags(const VolrenderFlags& f, const ViewParams& view) {
    const auto [width, height] = frameSize(view.width, view.height, layoutOf(f));
    checkViewOutput(f.output, "-o", width, height);
    if (!f.heatmap.empty()) checkViewOutput(f.heatmap, "--heatmap", width, height);
    if (!f.fps) return;
    if (!movieFormat(f.output) && !movieFormat(f.heatmap))
        throw InputError("--fps " + std::to_string(*f.fps) + ": a frame rate is for a movie (-o or --heatmap "
                         "NAME.gif or NAME.mp4), and " + f.output + " is an image");
    if (*f.fps < 1 || *f.fps > 60) throw InputError("--fps " + std::to_string(*f.fps) + ": must be in 1..60");
}

// --blend and --iso into the settings; auto leaps by blocks for the blends other than composite. Throws InputError
// for an unknown blend, an iso-value without the iso blend or the reverse, and a caster the blend cannot leap with.
void applyBlend(const VolrenderFlags& f, RenderSettings& s) {
    s.blend = parseBlend(f.blend);
    if (f.iso && s.blend != Blend::Iso)
        throw InputError("--iso is the iso-surface's value: it needs --blend iso (not --blend " + f.blend + ")");
    if (s.blend == Blend::Iso && !f.iso) throw InputError("--blend iso needs the iso-value: --iso VALUE");
    if (f.iso) s.isoValue = *f.iso;
    if (s.blend != Blend::Composite && f.caster == "auto") s.caster = Caster::Blocks;
    checkBlend(s);
}

}  // namespace

void addVolrenderFlags(CLI::App& app, VolrenderFlags& f) {
    app.add_option("input", f.input,
                   "prepared volume written by volprep, or a volume to prepare here (raw, NRRD, MetaImage, NIfTI, "
                   "VTI/VTK, VDB or a DICOM folder, as volprep reads them; needs --tf or --window/--level)");
    addVolumeFlags(app, f.volume);
    app.add_option("-o,--output", f.output, "image to write: .png (8-bit sRGB) or .exr (float RGBA); or a movie "
                                            "of the views: .gif (256 colours a frame) or .mp4 (H.264)");
    app.add_option("--caster", f.caster, "primitive, pc, acd, eacd, hier, blocks, or auto (composite: chosen from the "
                                         "file's ray probe and the views by a cost model, see --calibration; a "
                                         "volume prepared here: primitive, hier or EACD, whichever its views and "
                                         "the field's build cost least; the other blends: primitive or blocks, "
                                         "whichever the views probed cost least)")
        ->capture_default_str();
    app.add_option("--blend", f.blend, "what a ray shows: composite (front-to-back compositing of the classified "
                                       "samples), mip or minip (the largest or smallest scalar), average (the mean "
                                       "scalar), each in its transfer-function colour at its opacity (opaque with "
                                       "--window/--level: a grey window), or iso (the first crossing of --iso, shaded "
                                       "in its colour)")->capture_default_str();
    app.add_option("--iso", f.iso, "the iso-surface's scalar value (--blend iso)");
    CLI::Option* calibration = app.add_option(
        "--calibration", f.calibration,
        "the auto caster's cost constants, as auto_caster_bench --write-calibration measures them on a device "
        "(default: $XDG_CONFIG_HOME/volrender/calibration.json, else ~/.config/volrender/calibration.json, when "
        "measured on the device rendering; else built-in constants measured on lavapipe with 2 cores)");
    app.add_option("--size", f.size, "image size WIDTHxHEIGHT (1..16384 each)")->capture_default_str();
    addCameraFlags(app, f.camera);
    addClipFlags(app, f.clip);
    addStereoFlags(app, f.stereo);
    app.add_option("--step", f.step, "sampling step in voxels of the smallest spacing")->capture_default_str();
    app.add_option("--ert", f.ert, "early ray termination opacity, (0, 1]")->capture_default_str();
    app.add_option("--light", f.light, "direction toward a directional light x,y,z (default: headlight)")
        ->delimiter(',')->expected(3);
    app.add_flag("--no-shading", f.noShading, "emission-absorption only (no gradients are taken)");
    app.add_option("--gradients", f.gradients, "what shading takes its normals from: on-the-fly (central differences "
                   "at each shaded sample, nothing stored) or stored (each voxel's gradient in 4 more bytes per voxel "
                   "on the device: faster per frame on CPU devices, not on GPUs)")->capture_default_str();
    auto* trilinear = app.add_flag("--trilinear", f.trilinear,
                                   "trilinear sampling, the scalar interpolated then classified; the default");
    app.add_flag("--nearest", f.nearest, "nearest-voxel sampling instead of trilinear")->excludes(trilinear);
    app.add_flag("--jitter", f.jitter, "start each ray's samples a per-pixel fraction of a step late: fine noise "
                                       "instead of the wood-grain rings of a lattice shared by every ray");
    app.add_option("--background", f.background, "background colour r,g,b, each in [0, 1]")
        ->delimiter(',')
        ->expected(3);
    app.add_option("--stats", f.stats, "write timings, iterations per ray and uploaded bytes as JSON");
    app.add_option("--heatmap", f.heatmap, "write the iterations per pixel as a colour-mapped PNG (or a movie, as -o)");
    app.add_option("--views", f.views, "render an orbit of N views 360/N degrees apart about the view-up into "
                                       "NAME_000.EXT ..., or into the frames of a movie -o NAME.gif / NAME.mp4")
        ->capture_default_str();
    app.add_option("--fps", f.fps, "frames per second of a movie, 1..60 (default 25)");
    app.add_flag("--list-devices", f.listDevices, "list the Vulkan devices and exit");
    CLI::Option* device =
        app.add_option("--device", f.device, "Vulkan device index (see --list-devices; default: first discrete GPU)");
    // The CPU reference is on no device, and no calibration prices it.
    app.add_flag("--cpu", f.cpu, "render with the CPU reference instead of Vulkan")
        ->excludes(device)
        ->excludes(calibration);
    app.add_flag("-q,--quiet", f.quiet, "no progress bars and no report of the stages, the choice and the views: "
                                        "errors only");
}

std::optional<StereoLayout> layoutOf(const VolrenderFlags& f) {
    if (!f.stereo.separation) return std::nullopt;
    return stereoLayout(f.stereo);
}

int movieFps(const VolrenderFlags& f) { return f.fps.value_or(25); }

bool checkVolrenderFlags(const VolrenderFlags& f, ViewParams& view, RenderSettings& s) {
    if (f.input.empty()) throw InputError("no volume or prepared volume given (see --help)");
    if (f.output.empty()) throw InputError("no output image given: -o IMAGE");
    if (!fs::exists(f.input)) throw fileError(f.input, "no such file");
    const bool raw =
        !f.volume.dims.empty() || !f.volume.type.empty() || !f.volume.spacing.empty() || f.volume.bigEndian;
    const bool prepared = isPreparedFile(f.input);
    if (prepared) {
        if (!f.volume.transfer.empty() || raw)
            throw fileError(f.input, "a prepared file holds its transfer function and grid: --tf, --window, "
                                     "--level and the raw flags are for a volume to prepare");
        if (!f.volume.labels.empty() || !f.volume.labelColours.empty())
            throw fileError(f.input, "a prepared file holds its label map, if any: --labels and --label-colors "
                                     "are for a volume to prepare (volprep --labels puts them in the file)");
        if (f.volume.toGiven || f.volume.taGiven)
            throw fileError(f.input, "a prepared file holds its regions, made at its thresholds: --to and --ta are "
                                     "for a volume to prepare (volprep --to, --ta prepares it again)");
        if (!f.volume.series.empty())
            throw fileError(f.input, "--series picks a series of a DICOM folder; this is a prepared file");
    } else {
        if (f.volume.transfer.empty())
            throw fileError(f.input, "not a prepared file: a volume to prepare here needs --tf PRESET or "
                                     "--tf FILE.json, or --window and --level");
        checkThresholds(f.volume, !f.noShading);
    }
    long long w = 0, h = 0;  // wider than int: 4294967304x8 must not wrap around to 8x8
    char extra = 0;
    if (std::sscanf(f.size.c_str(), "%lldx%lld%c", &w, &h, &extra) != 2)
        throw InputError("--size '" + f.size + "': expected WIDTHxHEIGHT, e.g. 512x512");
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        throw InputError("--size " + f.size + ": width and height must be in 1..16384");
    checkStepAndTermination(f.step, f.ert);
    if (f.views < 1 || f.views > 3600) throw InputError("--views must be in 1..3600");
    view = viewParams(f.camera, int(w), int(h));
    checkStereoFlags(f.stereo, view.projection, f.cpu);
    checkMovieFlags(f, view);
    checkWritable(f.output, "the image");
    if (!f.heatmap.empty()) checkWritable(f.heatmap, "--heatmap");
    if (!f.stats.empty()) checkWritable(f.stats, "--stats");
    checkDistinctFiles(f);

    if (f.caster != "auto") s.caster = parseCaster(f.caster);
    s.stepVoxels = f.step;
    s.ert = f.ert;
    s.shading = !f.noShading;
    s.gradients = parseGradients(f.gradients);
    if (f.noShading && s.gradients == Gradients::Stored)
        throw InputError("--gradients stored: an unshaded render (--no-shading) takes no gradients");
    s.trilinear = !f.nearest;
    s.jitter = f.jitter;
    s.opaqueValues = f.volume.transfer.window.has_value();  // a grey window for MIP, MinIP and average
    applyClipFlags(f.clip, s);
    s.background = finiteVector(f.background, "--background");
    for (double c : {s.background.x, s.background.y, s.background.z})
        if (c < 0 || c > 1) throw InputError("--background: each component must be in [0, 1]");
    if (!f.light.empty()) {
        s.lightDirection = finiteVector(f.light, "--light");
        if (length(*s.lightDirection) == 0) throw InputError("--light: the direction must not be zero");
    }
    applyBlend(f, s);
    // A light and stored gradients serve the shading alone: composite and iso shade, MIP, MinIP and average do not.
    if (s.blend != Blend::Composite && s.blend != Blend::Iso) {
        if (s.lightDirection) throw InputError("--light with --blend " + f.blend + ": that blend is not shaded");
        if (s.gradients == Gradients::Stored)
            throw InputError("--gradients stored with --blend " + f.blend + ": that blend is not shaded");
    }
    if (s.lightDirection && !s.shading) throw InputError("--light: an unshaded render (--no-shading) takes no light");
    checkLabelledBlend(!f.volume.labels.empty(), s);
    if (!prepared) checkLabelFlags(f.volume);  // before the volume is read
    return prepared;
}

}  // namespace vr
