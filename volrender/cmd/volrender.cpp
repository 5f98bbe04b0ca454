// volrender: renders a prepared volume (volprep's output), or a volume it prepares in the same process, with one of
// the casters, on a Vulkan device or with the CPU reference; writes the image, optionally an iteration heat
// map and statistics.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>

#include "tools/heap_reuse.h"
#include "tools/peak_resident.h"
#include "tools/progress.h"
#include "tools/tool_main.h"
#include "core/errors.h"
#include "io/prepared_file.h"
#include "preprocess/cmd/volume_flags.h"
#include "preprocess/pipeline/hier_field.h"
#include "volrender/cmd/auto_caster.h"
#include "volrender/cmd/calibration_in_use.h"
#include "volrender/cmd/camera_flags.h"
#include "volrender/cmd/clip_flags.h"
#include "volrender/cmd/heatmap.h"
#include "volrender/cmd/opening_device.h"
#include "render/caster_choice.h"
#include "volrender/cmd/process_timeline.h"
#include "volrender/cmd/render_stats.h"
#include "volrender/cmd/stereo_flags.h"
#include "volrender/cmd/stereo_output.h"
#include "volrender/cmd/volrender_flags.h"
#include "render/cpu_renderer.h"
#include "render/render_checks.h"
#include "render/view_octants.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace {

constexpr vr::ToolText kText{
    "volrender",
    "Renders a volume (any format volprep reads, with --tf; prepared in memory) or a prepared volume (see volprep) "
    "by ray casting with homogeneous-region leaping: the primitive "
    "caster samples every step; pc, acd and eacd leap through regions with their distance fields, hier through "
    "blocks of 4^3 voxels with an EACD over them (built in a few ns per voxel, no segmentation), and all give the "
    "same image at thresholds 0; auto (the default) picks the cheapest for the views. Each sample is interpolated "
    "from the scalars (trilinear by default), classified through the transfer table and shaded from the scalars' "
    "gradient. --blend mip, minip, average or iso shows the largest, smallest or mean scalar, or the iso-surface of "
    "--iso VALUE, instead, leaping over blocks that cannot change it (--caster blocks). --stereo renders a pair "
    "whose right eye reuses the left eye's pixels. Runs on a Vulkan device (or --cpu).",
    "Exit status: 0 done, 1 bad input or device failure, 2 bad command line."};

using Flags = vr::VolrenderFlags;

// Seconds per stage of a volume prepared here (empty for a prepared file).
nlohmann::json prepareSeconds(const std::vector<vr::StageTime>& stages) {
    nlohmann::json seconds = nlohmann::json::object();
    for (const vr::StageTime& t : stages) seconds[t.stage] = t.seconds;
    return seconds;
}

unsigned fieldsFor(vr::Caster c) {
    switch (c) {
        case vr::Caster::Primitive: return 0;
        case vr::Caster::PC: return vr::kFieldPC;
        case vr::Caster::ACD: return vr::kFieldACD;
        case vr::Caster::EACD: return vr::kFieldEACD;
        case vr::Caster::Blocks: return 0;  // built from the scalars
        case vr::Caster::Hier: return vr::kFieldHier;  // built from the scalars and their classification
    }
    return 0;
}

// The cameras of the views, both eyes of each pair with --stereo: the ones the casters see (their rays' octants).
std::vector<vr::Camera> eyeCameras(const Flags& f, const vr::GridGeometry& grid, const vr::ViewParams& view) {
    const std::vector<vr::Camera> cameras = vr::Camera::orbit(grid, view, f.views);
    if (!f.stereo.separation) return cameras;
    std::vector<vr::Camera> eyes;
    for (const vr::Camera& camera : cameras) {
        const vr::StereoPair pair = vr::stereoPair(camera, grid, *f.stereo.separation, f.stereo.focus);
        eyes.push_back(pair.left);
        eyes.push_back(pair.right);
    }
    return eyes;
}

// Whether the views are stereo pairs whose right eyes reuse their left (their pipelines are made ahead).
bool pairsWithReuse(const Flags& f) { return f.stereo.separation && vr::stereoReuse(f.stereo, f.cpu); }

// The octants of every ray of the cameras.
unsigned orbitOctants(const std::vector<vr::Camera>& cameras) {
    unsigned octants = 0;
    for (const vr::Camera& camera : cameras) octants |= vr::viewOctants(camera);
    return octants;
}

// A prepared file with what the caster reads: its field's chunks in the orbit's octants (no region labels), or for
// hier (which no file holds) the field built from the file's scalars and classification for those octants, with the
// file's thresholds. The scalars stay in their own type where the device's upload is all that reads them: a
// composite render on the device, without hier's build or stored gradients (at 512^3 int16: 512 MiB less).
vr::PreparedVolume readPreparedFor(const Flags& f, const vr::RenderSettings& s, bool onDevice,
                                   const vr::ViewParams& view, const vr::GridGeometry& grid) {
    const vr::Caster caster = s.caster;
    const unsigned octants = orbitOctants(eyeCameras(f, grid, view));
    const bool uploadOnly = onDevice && s.blend == vr::Blend::Composite && caster != vr::Caster::Hier &&
                            !s.readsStoredGradients();
    vr::PreparedVolume prepared = vr::readPrepared(f.input, fieldsFor(caster), {octants, false, !uploadOnly});
    if (caster == vr::Caster::Hier)
        prepared.fields.hier = vr::buildHierarchicalEACD(prepared, prepared.meta.segmentation, octants);
    return prepared;
}

// The one-command path: the volume loaded, classified, segmented and given the field of the caster only, in the
// octants of the orbit's rays only (regions for the sampling and shading asked), in memory, each stage timed. The
// `device` (none for the CPU reference) makes its pipelines meanwhile. With `chooseHere`, --caster auto picks the
// caster for the device between classifying and segmenting (a primitive, hier or blocks render segments nothing) and
// says why in `choice`.
vr::PreparedVolume prepareVolume(const Flags& f, const vr::ViewParams& view, vr::RenderSettings& s,
                                 vr::OpeningDevice* device, bool chooseHere, std::string& choice,
                                 std::vector<vr::StageTime>& stages) {
    vr::PrepareOptions options = vr::prepareOptionsFrom(f.volume, !s.trilinear, !s.shading);
    options.fields = fieldsFor(s.caster);
    options.keepRegions = false;  // the renderers read the field, never the labels: freed once the field has them
    const auto labelColours = vr::checkLabelFlags(f.volume);
    vr::StagedPreparation staged = vr::StagedPreparation::load(f.input, vr::rawOptionsFrom(f.volume));
    if (!f.quiet)
        for (const std::string& note : staged.volume().notes)
            std::fprintf(stderr, "volrender: %s: %s\n", f.input.c_str(), note.c_str());
    vr::attachLabels(f.volume, labelColours, staged);
    const std::vector<vr::Camera> cameras = eyeCameras(f, staged.volume().grid, view);
    options.octants = orbitOctants(cameras);
    // Auto for another blend chooses within a few ms of classifying: its pipeline is made once chosen, rather than
    // a guess's first (a CPU device takes 0.1-0.2 s over one).
    const bool composite = s.blend == vr::Blend::Composite;
    const bool makeAhead = device && f.volume.labels.empty();
    // Auto takes hier for most CTs, else the primitive caster or, for a small volume, EACD; chosen before the device
    // has opened (the usual case), its pipeline alone is made.
    if (makeAhead && (composite || !chooseHere))
        device->preparePipelines(chooseHere ? std::vector{vr::Caster::Hier, vr::Caster::Primitive, vr::Caster::EACD}
                                            : std::vector{s.caster},
                                 s, cameras.front().projection, staged.volume().sourceType, pairsWithReuse(f));
    if (chooseHere) {
        const auto blendCalibration = [&] {
            return vr::calibrationInUse(f.calibration, vr::deviceToCalibrate(f.calibration, *device)).constants;
        };
        const vr::CasterChoice c =
            composite ? vr::autoCasterBeforeFields(f.calibration, s, staged, options, cameras, *device)
                      : vr::autoBlendCaster(staged.prepare(options, vr::PrepStage::Classify), s, cameras,
                                            blendCalibration());
        s.caster = c.caster;
        choice = c.reason;
        device->chose(s.caster);
        if (makeAhead && !composite)
            device->preparePipelines({s.caster}, s, cameras.front().projection, staged.volume().sourceType,
                                     pairsWithReuse(f));
        options.fields = fieldsFor(s.caster);
    }
    staged.prepare(options);
    stages = staged.stageTimes();
    if (!f.quiet) {
        std::printf("prepared:");
        for (const vr::StageTime& t : stages) std::printf(" %s %.3f s", t.stage.c_str(), t.seconds);
        std::printf("\n");
    }
    return std::move(staged).takeResult();
}

// One view's images: one, or a stereo pair's left and right eye.
struct RenderedView {
    std::vector<vr::RenderResult> results;
    std::vector<vr::UploadedResource> uploads;  // on the device for it (none for the CPU reference)
    nlohmann::json stereo;                      // a pair's reuse: the fraction re-cast, the reprojection's time
};

// A view's statistics: its one image's, or each eye's of a pair (and the pair's device time).
nlohmann::json frameStatistics(const RenderedView& view) {
    if (view.results.size() == 1) return vr::viewStatistics(view.results.front(), view.uploads);
    nlohmann::json s = view.stereo;
    s["left"] = vr::viewStatistics(view.results[0], view.uploads);
    s["right"] = vr::viewStatistics(view.results[1], view.uploads);
    s["deviceMs"] = view.results[0].deviceMilliseconds + view.results[1].deviceMilliseconds;
    s["wallMs"] = view.results[0].wallMilliseconds + view.results[1].wallMilliseconds;
    // Where both eyes' rays were counted: a left eye reprojected by depth interval (the blends but composite) counts
    // its rays for the reprojection, the right eye only when the counts were asked for.
    const nlohmann::json &left = s.at("left"), &right = s.at("right");
    if (left.contains("iterationsPerRay") && right.contains("iterationsPerRay"))
        s["iterationsPerRay"] = {{"mean", (left["iterationsPerRay"]["mean"].get<double>() +
                                           right["iterationsPerRay"]["mean"].get<double>()) / 2}};
    return s;
}

// The iterations per ray of a view's report, where its rays were counted.
std::string iterationsNote(std::optional<double> perRay) {
    if (!perRay) return "";
    char text[64];
    std::snprintf(text, sizeof text, ", %.1f iterations per ray", *perRay);
    return text;
}

// A pair's eyes' device times and the right eye's pixels cast again, for the report of a view.
std::string stereoNote(const RenderedView& view) {
    if (view.results.size() < 2) return "";
    char text[160];
    std::snprintf(text, sizeof text, " (left %.2f ms, right %.2f ms device, %.1f %% of the right eye cast)",
                  view.results[0].deviceMilliseconds, view.results[1].deviceMilliseconds,
                  100 * view.stereo.value("recastFraction", 1.0));
    return text;
}

// Renders the views into their outputs in order: each an image file (a line each), or a frame of a movie (a
// progress bar over the frames, then one line). Returns each view's statistics.
nlohmann::json renderViews(const Flags& f, int count, int width, int height, vr::Caster caster,
                           const std::function<RenderedView(int)>& render) {
    const vr::MovieSpec spec{width, height, f.views, vr::movieFps(f)};
    vr::FrameOutput images(f.output, spec, vr::layoutOf(f));
    std::optional<vr::FrameOutput> heatmaps;
    if (!f.heatmap.empty()) heatmaps.emplace(f.heatmap, spec, vr::layoutOf(f));
    std::optional<vr::ProgressBar> frames;
    if (images.isMovie()) frames.emplace("frames", f.views);
    nlohmann::json viewStats = nlohmann::json::array();
    double deviceMs = 0, wallMs = 0;              // summed over the views
    std::optional<double> iterations;             // per ray, summed over the views where their rays were counted
    for (int i = 0; i < count; ++i) {
        RenderedView view = render(i);
        if (i == 0) vr::markMilestone("firstViewRendered");
        std::vector<vr::Image> pictures, heat;
        for (vr::RenderResult& result : view.results) {
            pictures.push_back(std::move(result.image));  // not copied: 64 MB at 2048 x 2048; the statistics need none
            if (heatmaps) heat.push_back(vr::iterationHeatmap(result.iterations, width, height));
        }
        images.add(i, pictures);
        if (heatmaps) heatmaps->add(i, heat);
        nlohmann::json s = frameStatistics(view);
        s["image"] = images.name(i);
        if (images.isMovie()) s["frame"] = i;
        s["orbit"] = 360.0 * i / f.views;  // degrees about the view-up
        viewStats.push_back(s);
        deviceMs += s["deviceMs"].get<double>();
        wallMs += s["wallMs"].get<double>();
        std::optional<double> perRay;  // where the rays were counted (--stats, --heatmap)
        if (s.contains("iterationsPerRay")) perRay = s["iterationsPerRay"]["mean"].get<double>();
        if (perRay) iterations = iterations.value_or(0) + *perRay;
        if (frames)
            frames->advance();
        else if (!f.quiet)
            std::printf("%s: %s caster, %.2f ms device, %.2f ms wall%s%s\n", images.name(i).c_str(),
                        vr::casterName(caster).data(), s["deviceMs"].get<double>(), s["wallMs"].get<double>(),
                        iterationsNote(perRay).c_str(), stereoNote(view).c_str());
    }
    images.finish();
    if (heatmaps) heatmaps->finish();
    if (!frames) return viewStats;
    frames->finish();
    if (!f.quiet)
        std::printf("%s: %d frames, %s caster, per frame %.2f ms device, %.2f ms wall%s\n", f.output.c_str(),
                    f.views, vr::casterName(caster).data(), deviceMs / f.views, wallMs / f.views,
                    iterationsNote(iterations ? std::optional(*iterations / f.views) : std::nullopt).c_str());
    return viewStats;
}

// Every output is written and closed: the process ends without tearing the device down. On an H100 the driver's
// teardown (the device, the instance, its libraries) took 20 ms of a 0.22 s one-view render, which the kernel's
// cleanup of the process makes needless. Sanitizer builds end normally, so that the leak checker runs.
int exitWithoutTeardown() {
#ifndef VR_SANITIZED
    std::fflush(nullptr);
    std::_Exit(0);
#endif
    return 0;
}

int run(const Flags& f) {
    if (f.listDevices) {
        const auto devices = vr::VulkanContext::listDevices();
        if (devices.empty()) throw std::runtime_error("no Vulkan device found (is a Vulkan driver installed?)");
        for (const auto& d : devices)
            std::printf("%d: %s (%s, Vulkan %s)\n", d.index, d.name.c_str(), d.type.c_str(), d.apiVersion.c_str());
        return 0;
    }
    vr::ViewParams view;
    vr::RenderSettings settings;
    const bool prepareHere = !vr::checkVolrenderFlags(f, view, settings);
    // Each ray's counts only where an output shows them: without, a device copies back half the bytes a view.
    settings.rayCounts = !f.stats.empty() || !f.heatmap.empty();
    if (f.quiet) vr::ProgressBar::silenceAll();
    std::string choice;  // why --caster auto chose its caster
    const bool chooseCaster = f.caster == "auto";
    const bool composite = settings.blend == vr::Blend::Composite;
    if (chooseCaster && !composite)  // the CPU reference's choice; a device's weighs it against the primitive caster
        choice = "the " + f.blend + " blend leaps by the blocks' scalar extrema";
    if (prepareHere && chooseCaster && composite) {  // the device's choice is made between classifying and segmenting
        settings.caster = vr::Caster::EACD;
        choice = "the CPU reference has no calibration to weigh the casters: EACD, which leaps furthest";
    }
    std::optional<vr::OpeningDevice> device;
    if (!f.cpu) device.emplace(f.device);
    std::vector<vr::StageTime> stages;  // of preparing the volume here
    std::optional<vr::PreparedVolume> preparedHere;
    if (prepareHere)
        preparedHere = prepareVolume(f, view, settings, device ? &*device : nullptr, chooseCaster && device, choice,
                                     stages);
    // Before a prepared file is read: auto weighs the casters with the constants measured on the device.
    vr::VulkanContext* context = device ? &device->context() : nullptr;
    vr::VulkanRenderer* renderer = device ? &device->renderer() : nullptr;
    const vr::CalibrationInUse calibration =
        vr::calibrationInUse(f.calibration, context ? std::optional(context->info().name) : std::nullopt);
    // A prepared file's header: what auto weighs and what the device's pipeline is made for.
    const std::optional<vr::PreparedHeader> header =
        prepareHere ? std::nullopt : std::optional(vr::readPreparedHeader(f.input));
    if (chooseCaster && composite && header) {
        if (!calibration.note.empty() && !f.quiet) std::fprintf(stderr, "volrender: %s\n", calibration.note.c_str());
        const vr::CasterChoice c =
            vr::autoCasterForFile(*header, eyeCameras(f, header->grid, view), settings, calibration.constants);
        settings.caster = c.caster;
        choice = c.reason;
    }
    // Another blend's choice on the device needs the scalars: made once the file is read, and its pipeline then.
    const bool chooseAfterReading = chooseCaster && !composite && header && device;
    // Else the device makes the caster's pipeline while the file is read.
    const bool makeAhead = device && header && std::none_of(header->chunks.begin(), header->chunks.end(),
                                                            [](const vr::PreparedChunkBytes& c) {
                                                                return c.name == "labelMap";
                                                            });
    auto makePipeline = [&] {
        device->preparePipelines({settings.caster}, settings,
                                 eyeCameras(f, header->grid, view).front().projection, header->scalarType,
                                 pairsWithReuse(f));
    };
    if (makeAhead && !chooseAfterReading) makePipeline();
    const vr::PreparedVolume prepared =
        prepareHere ? std::move(*preparedHere) : readPreparedFor(f, settings, renderer != nullptr, view, header->grid);
    if (chooseAfterReading) {
        const vr::CasterChoice c =
            vr::autoBlendCaster(prepared, settings, eyeCameras(f, prepared.grid(), view), calibration.constants);
        settings.caster = c.caster;
        choice = c.reason;
        if (makeAhead) makePipeline();
    }
    vr::markMilestone("volumeReady");
    if (chooseCaster && !f.quiet)
        std::fprintf(stderr, "volrender: --caster auto chose %s: %s\n", vr::casterName(settings.caster).data(),
                     choice.c_str());

    const std::vector<vr::Camera> cameras = vr::Camera::orbit(prepared.grid(), view, f.views);
    const unsigned octants = orbitOctants(eyeCameras(f, prepared.grid(), view));  // the orbit shares one upload
    std::optional<vr::GpuVolume> uploaded;
    nlohmann::json uploadStats;
    if (renderer) {
        const auto start = std::chrono::steady_clock::now();
        uploaded.emplace(renderer->upload(prepared, {{settings.caster}, octants, settings.readsStoredGradients()}));
        vr::markMilestone("uploaded");
        uploadStats = vr::uploadStatistics(
            *uploaded, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        if (!f.quiet)
            std::printf("upload: %.2f ms, %.1f MB in %zu brick(s)\n", uploadStats["milliseconds"].get<double>(),
                        double(uploaded->uploadedBytes()) / 1e6, uploaded->bricks().bricks().size());
    }
    vr::keepViewBlocksInTheHeap();
    const bool reuse = vr::stereoReuse(f.stereo, f.cpu);
    const nlohmann::json viewStats = renderViews(f, f.views, view.width, view.height, settings.caster, [&](int i) {
        const vr::Camera& camera = cameras[i];
        if (!f.stereo.separation) {
            if (!renderer) return RenderedView{{vr::renderCpu(prepared, camera, settings)}, {}, {}};
            vr::RenderResult result = renderer->render(*uploaded, camera, settings);
            return RenderedView{{std::move(result)}, renderer->lastUploads(), {}};
        }
        const vr::StereoPair pair = vr::stereoPair(camera, prepared.grid(), *f.stereo.separation, f.stereo.focus);
        if (!renderer)
            return RenderedView{
                {vr::renderCpu(prepared, pair.left, settings), vr::renderCpu(prepared, pair.right, settings)},
                {},
                {{"recastFraction", 1.0},
                 {"recastInPartFraction", 0.0},
                 {"recastPieces", 1},
                 {"reprojectMs", 0.0},
                 {"focus", pair.focus}}};
        vr::StereoRender stereo = renderer->renderStereo(*uploaded, pair, settings, reuse);
        return RenderedView{{std::move(stereo.left), std::move(stereo.right)}, renderer->lastUploads(),
                            {{"recastFraction", stereo.recastFraction},
                             {"recastInPartFraction", stereo.recastInPartFraction},
                             {"recastPieces", stereo.recastPieces},
                             {"reprojectMs", stereo.reprojectMilliseconds}, {"focus", pair.focus}}};
    });
    vr::markMilestone("imagesWritten");
    if (context)  // only with VR_VALIDATION=1: what the validation layer reported
        for (const std::string& message : context->validationErrors())
            std::fprintf(stderr, "volrender: validation error: %s\n", message.c_str());
    if (!f.stats.empty()) {
        nlohmann::json settingsStats{
            {"caster", vr::casterName(settings.caster)}, {"casterAsked", f.caster}, {"casterChoice", choice},
            {"size", f.size}, {"step", f.step}, {"ert", f.ert}, {"shading", settings.shading},
            {"gradients", vr::gradientsName(settings.gradients)}, {"trilinear", settings.trilinear},
            {"jitter", settings.jitter}, {"light", f.light}, {"background", f.background}, {"views", f.views},
            {"fps", vr::movieFps(f)}, {"blend", f.blend}, {"iso", f.iso ? nlohmann::json(*f.iso) : nlohmann::json()}};
        settingsStats.update(vr::cameraStatistics(f.camera));
        settingsStats.update(vr::clipStatistics(f.clip));
        settingsStats.update(vr::stereoStatistics(f.stereo, f.cpu));
        nlohmann::json stats{
            {"prepared", f.input},
            {"renderer", context ? context->info().name : std::string("cpu reference")},
            {"settings", settingsStats},
            {"calibration", vr::calibrationStatistics(calibration)},
            {"prepareSeconds", prepareSeconds(stages)},
            {"upload", uploadStats},
            {"views", viewStats},
            {"peakResidentBytes", vr::peakResidentBytes()},  // the whole process so far: load to the last image
            {"timelineMs", vr::processTimeline()}};
        std::ofstream(f.stats) << stats.dump(2) << "\n";
    }
    return exitWithoutTeardown();
}

}  // namespace

int main(int argc, char** argv) {
    return vr::runTool<Flags>(kText, argc, argv, vr::addVolrenderFlags, [](const Flags& flags) {
        try {
            return run(flags);
        } catch (const vk::SystemError& e) {  // e.g. no driver: say it is Vulkan's, and what still works
            throw std::runtime_error(std::string("Vulkan error: ") + e.what() + " (--cpu renders without a device)");
        }
    });
}
