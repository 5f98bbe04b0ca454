#include "sweep/run_sweep.h"

#include <cstdio>
#include <map>
#include <set>

#include "io/atomic_file.h"
#include "core/errors.h"
#include "tools/progress.h"
#include "preprocess/classify/transfer_choice.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "sweep/downsample.h"
#include "sweep/order_statistics.h"
#include "sweep/peer_comparison.h"
#include "sweep/stereo_row.h"
#include "sweep/sweep_row.h"
#include "render/camera.h"
#include "render/view_octants.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {
namespace fs = std::filesystem;

fs::path imagesDir(const fs::path& outDir, const std::string& dataset) { return outDir / "images" / dataset; }

std::string imageName(const std::string& caster, double to, double ta, bool errorMap) {
    return caster + "_" + thresholdText(to) + "_" + thresholdText(ta) + (errorMap ? "_error" : "") + ".png";
}

namespace {

struct View {
    double azimuth, elevation;
    Camera camera;
};

std::vector<View> orbit(const SweepOptions& o, const GridGeometry& grid) {
    std::vector<View> views;
    for (double elevation : o.elevations)
        for (int i = 0; i < o.views; ++i) {
            ViewParams p;
            p.azimuthDeg = 360.0 * i / o.views;
            p.elevationDeg = elevation;
            p.width = o.width;
            p.height = o.height;
            views.push_back({p.azimuthDeg, elevation, Camera::fit(grid, p)});
        }
    return views;
}

// Device time where the queue has timestamps, else wall time (both from the same frame).
double frameMs(const RenderResult& r) { return r.deviceMilliseconds > 0 ? r.deviceMilliseconds : r.wallMilliseconds; }

unsigned fieldsFor(const std::vector<Caster>& casters) {
    unsigned kinds = 0;
    for (Caster c : casters)
        kinds |= c == Caster::PC ? kFieldPC : c == Caster::ACD ? kFieldACD : c == Caster::EACD ? kFieldEACD : 0u;
    return kinds;
}

long long fieldBytes(const DistanceFields& f, Caster c) {
    switch (c) {
        case Caster::Primitive: return 0;
        case Caster::PC: return (long long)f.pc.size();
        case Caster::ACD: return (long long)(f.acd[0].size() * kOctants);
        case Caster::EACD: return (long long)(f.eacd[0].bytes() * kOctants);
        case Caster::Blocks: return 0;  // built at render time from the scalars
        case Caster::Hier: return (long long)f.hier.bytes();
    }
    return 0;
}

// The wall seconds of the stages the preparation ran for one setting (segmentation and the fields), into `row`.
void recordStages(const StagedPreparation& staged, const PreparedVolume& p, SweepRow& row) {
    for (const StageTime& t : staged.lastStages()) {
        if (t.stage == "segment") row.segmentSeconds = t.seconds;
        if (t.stage == "pc") row.pcSeconds = t.seconds;
        if (t.stage == "acd") row.acdSeconds = t.seconds;
        if (t.stage == "eacd") row.eacdSeconds = t.seconds;
    }
    row.regions = p.regions.count;
}

// One caster's measurements over the views of one setting.
struct CasterRun {
    RenderSettings settings;
    std::vector<double> device, wall;
    std::vector<uint32_t> iterations;
    std::vector<ImageError> errors;
    long long uploadedBytes = 0;

    void record(const RenderResult& r, const ImageError& error, const std::vector<UploadedResource>& uploads) {
        device.push_back(frameMs(r));
        wall.push_back(r.wallMilliseconds);
        iterations.insert(iterations.end(), r.iterations.begin(), r.iterations.end());
        errors.push_back(error);
        uploadedBytes = 0;
        for (const UploadedResource& u : uploads) uploadedBytes += (long long)u.bytes;
    }

    SweepRow row(SweepRow r, const DistanceFields& fields) const {
        r.caster = std::string(casterName(settings.caster));
        r.deviceMsMedian = median(device);
        r.deviceMsP95 = percentile(device, 0.95);
        r.wallMsMedian = median(wall);
        double sum = 0;
        for (uint32_t i : iterations) sum += i;
        r.iterationsMean = iterations.empty() ? 0 : sum / double(iterations.size());
        r.iterationsP95 = percentile(iterations, 0.95);
        r.iterationsMax = percentile(iterations, 1.0);
        r.fieldBytes = fieldBytes(fields, settings.caster);
        r.uploadedBytes = uploadedBytes;
        r.error = summarize(errors);
        return r;
    }
};

// Every caster at every view, the casters taking turns within a view so that a busy machine slows them alike
// (the ratios are what holds); view 0's image and error map of each caster are written.
void renderSetting(VulkanRenderer& renderer, const PreparedVolume& p, const std::vector<View>& views,
                   const std::vector<Image>& references, std::vector<CasterRun>& runs, const SweepRow& setting,
                   const fs::path& images, ProgressBar& bar) {
    // One upload serves every caster and view of the setting (each render reads its part of it).
    GpuVolumeContents contents{{}, 0};
    for (const CasterRun& run : runs) contents.casters.push_back(run.settings.caster);
    for (const View& view : views) contents.octants |= viewOctants(view.camera);
    const GpuVolume volume = renderer.upload(p, contents);
    for (std::size_t v = 0; v < views.size(); ++v)
        for (CasterRun& run : runs) {
            const RenderResult r = renderer.render(volume, views[v].camera, run.settings);
            run.record(r, imageError(references[v], r.image), renderer.lastUploads());
            if (v == 0) {
                const std::string caster(casterName(run.settings.caster));
                const double to = setting.opacityThreshold, ta = setting.angleThreshold;
                writeImage(images / imageName(caster, to, ta, false), r.image);
                writeImage(images / imageName(caster, to, ta, true), errorMap(references[v], r.image));
            }
            bar.advance();
        }
}

// The (T_o, T_a) settings to run: all, or with resume those whose rows are not all in the CSV yet. Without resume
// a setting already there is an InputError (appending would give it twice); so are rows of the dataset rendered
// otherwise (another size, orbit, transfer function, sampling, step, ...), which the report would compare as alike.
std::vector<std::pair<double, double>> pendingSettings(const SweepOptions& o, const std::string& dataset,
                                                       const fs::path& csv) {
    std::set<std::string> done;
    const auto made = [](int width, int height, int views, const std::string& render) {
        return std::to_string(width) + "x" + std::to_string(height) + ", " + std::to_string(views) + " views, " +
               render;
    };
    const std::string here = made(o.width, o.height, int(o.views * o.elevations.size()), o.renderSettings());
    const auto compare = [&](const fs::path& file, const std::string& there) {
        if (there != here)
            throw fileError(file.string(), "holds rows of " + dataset + " rendered at " + there + "; this sweep "
                                           "renders at " + here + ": give it another --name, or another -o");
    };
    for (const SweepRow& r : readSweepCsv(csv)) {
        done.insert(r.key());
        if (r.dataset == dataset) compare(csv, made(r.width, r.height, r.views, r.render));
    }
    const fs::path stereo = csv.parent_path() / "stereo.csv";  // measured once per dataset, before its settings
    for (const StereoRow& r : readStereoCsv(stereo))
        if (r.dataset == dataset) compare(stereo, made(r.width, r.height, r.views, r.render));
    std::vector<std::pair<double, double>> settings;
    for (double to : o.opacityThresholds)
        for (double ta : o.angleThresholds) {
            bool all = o.resume;
            for (Caster c : o.casters) all = all && done.count(rowKey(dataset, to, ta, std::string(casterName(c))));
            if (!all) settings.emplace_back(to, ta);
            if (!o.resume && done.count(rowKey(dataset, to, ta, "primitive")))
                throw fileError(csv.string(), "already holds rows of " + dataset + " at T_o " + thresholdText(to) +
                                                  ", T_a " + thresholdText(ta) + ": pass --resume or another -o");
        }
    return settings;
}

// The sweep's classification (its TF, normals for shading) and the fields its casters read.
PrepareOptions prepareOptions(const SweepOptions& o) {
    PrepareOptions options;
    options.classify.transferFunction = chooseTransferFunction(o.transfer);
    options.classify.normals = o.shading;
    options.fields = fieldsFor(o.casters);
    return options;
}

// Classifies: the classification does not depend on the thresholds, so it is done once.
const PreparedVolume& classifyOnce(StagedPreparation& staged, const PrepareOptions& options,
                                   const std::string& dataset, std::size_t settings) {
    const PreparedVolume& p = staged.prepare(options, PrepStage::Classify);
    const Vec3i dims = p.grid().dims;
    std::fprintf(stderr, "%s: %dx%dx%d voxels", dataset.c_str(), dims.x, dims.y, dims.z);
    for (const StageTime& t : staged.stageTimes()) std::fprintf(stderr, ", %s %.2f s", t.stage.c_str(), t.seconds);
    std::fprintf(stderr, ", %zu settings to run\n", settings);
    return p;
}

// The dataset's stereo row (docs/BENCH.md "Stereo pairs"), unless stereo.csv has it: pairs about the orbit's views
// in perspective, with the primitive caster at thresholds 0 (the upload of the reference); view 0's reused right eye
// and its error map are written.
void measureStereoRow(const SweepOptions& o, const std::string& dataset, VulkanRenderer& renderer,
                      const GpuVolume& volume, const std::vector<View>& views, const RenderSettings& settings,
                      const fs::path& images) {
    const fs::path csv = o.outDir / "stereo.csv";
    for (const StereoRow& r : readStereoCsv(csv))
        if (r.dataset == dataset) return;
    std::vector<Camera> cameras;
    for (const View& v : views) {
        ViewParams p;
        p.projection = Projection::Perspective;
        p.azimuthDeg = v.azimuth;
        p.elevationDeg = v.elevation;
        p.width = o.width;
        p.height = o.height;
        cameras.push_back(Camera::fit(volume.grid(), p));
    }
    const StereoMeasurement m = measureStereo(renderer, volume, cameras, settings);
    appendStereoCsv(csv, StereoRow::of(dataset, settings.caster, o.width, o.height, int(views.size()),
                                       o.renderSettings(), m));
    writeImage(images / "stereo_right.png", m.reusedRight.front());
    writeImage(images / "stereo_right_error.png", errorMap(m.fullRight.front(), m.reusedRight.front()));
}

}  // namespace

int runSweep(const SweepOptions& o) {
    o.validate();
    const std::string dataset = o.datasetName();
    const fs::path csv = o.outDir / "sweep.csv";
    const fs::path images = imagesDir(o.outDir, dataset);

    const std::vector<std::pair<double, double>> settings = pendingSettings(o, dataset, csv);

    // Load and classify once; per setting the staged preparation re-runs only segmentation and the fields. The
    // transfer function is chosen first: a bad one fails before the load.
    PrepareOptions options = prepareOptions(o);
    StagedPreparation staged = o.downsample > 1
                                   ? StagedPreparation(downsample(loadVolume(o.input, o.raw), o.downsample))
                                   : StagedPreparation::load(o.input, o.raw);
    const PreparedVolume& p = classifyOnce(staged, options, dataset, settings.size());
    fs::create_directories(images);

    VulkanContext context(VulkanOptions{o.device, false});
    VulkanRenderer renderer(context);
    RenderSettings base;
    base.stepVoxels = o.stepVoxels;
    base.shading = o.shading;
    base.trilinear = o.trilinear;
    base.jitter = o.jitter;
    const std::vector<View> views = orbit(o, p.grid());

    // The reference: the primitive caster at T_o = T_a = 0 (it reads no regions or fields), once per view, never
    // jittered.
    std::vector<Image> references;
    std::map<double, Image> elevationZero;
    // These renders are also the primitive caster's row at every setting: it reads no regions or fields, so its
    // images and times do not depend on the thresholds (rendering it again per setting would only repeat them).
    // With jitter, its row is its jittered renders, against the reference.
    const GpuVolume volume = renderer.upload(p, {{Caster::Primitive}, 0});  // for every view
    CasterRun primitive;
    primitive.settings = base;
    primitive.settings.jitter = o.jitter;
    RenderSettings reference = base;
    reference.jitter = false;
    renderer.render(volume, views.front().camera, base);  // warm-up
    for (const View& v : views) {
        const RenderResult r = renderer.render(volume, v.camera, reference);
        references.push_back(r.image);
        if (v.elevation == 0) elevationZero[v.azimuth] = references.back();
        const RenderResult row = o.jitter ? renderer.render(volume, v.camera, primitive.settings) : r;
        primitive.record(row, imageError(r.image, row.image), renderer.lastUploads());
    }
    writeImage(images / "reference.png", references.front());
    if (!o.peersDir.empty()) {
        const nlohmann::json peers = comparePeers(o.peersDir, elevationZero);
        writeFileAtomically(o.outDir / ("peers_" + dataset + ".json"),
                            [&](std::ostream& s) { s << peers.dump(2) << '\n'; });
    }
    measureStereoRow(o, dataset, renderer, volume, views, base, images);
    if (settings.empty()) return 0;

    ProgressBar bar("sweep " + dataset, settings.size() * (o.casters.size() - 1) * views.size());
    std::set<Caster> warmed;
    for (const auto& [to, ta] : settings) {
        SweepRow row;
        row.dataset = dataset;
        row.opacityThreshold = to;
        row.angleThreshold = ta;
        row.views = int(views.size());
        row.width = o.width;
        row.height = o.height;
        row.render = o.renderSettings();
        options.segmentation = SegmentationParams{to, ta, o.shading, o.trilinear};
        staged.prepare(options);
        recordStages(staged, p, row);
        std::vector<CasterRun> runs;
        for (Caster c : o.casters) {
            if (c == Caster::Primitive) continue;  // its row comes from the reference's renders
            runs.push_back({});
            runs.back().settings = base;
            runs.back().settings.caster = c;
            if (warmed.insert(c).second) renderer.render(p, views.front().camera, runs.back().settings);  // warm-up
        }
        if (!runs.empty()) renderSetting(renderer, p, views, references, runs, row, images, bar);
        std::vector<SweepRow> rows{primitive.row(row, p.fields)};
        for (const CasterRun& run : runs) rows.push_back(run.row(row, p.fields));
        double primitiveMs = 0;
        for (const SweepRow& r : rows)
            if (r.caster == "primitive") primitiveMs = r.deviceMsMedian;
        for (SweepRow& r : rows) r.ratioToPrimitive = primitiveMs > 0 ? r.deviceMsMedian / primitiveMs : 0;
        appendSweepCsv(csv, rows);
    }
    bar.finish();
    return int(settings.size());
}

}  // namespace vr
