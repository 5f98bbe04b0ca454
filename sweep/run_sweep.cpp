#include "sweep/run_sweep.h"

#include <cstdio>
#include <map>
#include <set>

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/progress.h"
#include "preprocess/classify/classify.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/prepare.h"
#include "preprocess/segment/segment.h"
#include "sweep/order_statistics.h"
#include "sweep/peer_comparison.h"
#include "sweep/sweep_row.h"
#include "volrender/camera.h"
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
        case Caster::EACD: return (long long)(f.eacd[0].size() * kOctants * 3);
    }
    return 0;
}

// Segment and build the fields at one setting, recording each stage's wall seconds in `row`.
void prepareSetting(PreparedVolume& p, const SegmentationParams& params, unsigned kinds, SweepRow& row) {
    p.regions = {};
    p.fields = {};
    StageClock segmenting;
    p.regions = segment(p.classified, params);
    row.segmentSeconds = segmenting.stop("segment").seconds;
    p.fields.dims = p.regions.dims;
    if (kinds & kFieldPC) {
        StageClock clock;
        p.fields.pc = buildPC(p.regions);
        row.pcSeconds = clock.stop("pc").seconds;
    }
    if (kinds & (kFieldACD | kFieldEACD)) {
        StageClock clock;
        for (int o = 0; o < kOctants; ++o) p.fields.acd[o] = buildACD(p.regions, o);
        row.acdSeconds = clock.stop("acd").seconds;
    }
    if (kinds & kFieldEACD) {
        StageClock clock;
        p.fields.eacd = buildEACD(p.regions, p.fields.acd);
        row.eacdSeconds = clock.stop("eacd").seconds;
    }
    p.meta.segmentation = params;
    row.regions = p.regions.count;
}

// One caster's measurements over the views of one setting.
struct CasterRun {
    RenderSettings settings;
    std::vector<double> device, wall;
    std::vector<uint32_t> iterations;
    std::vector<ImageError> errors;
    long long uploadedBytes = 0;

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
    for (std::size_t v = 0; v < views.size(); ++v)
        for (CasterRun& run : runs) {
            const RenderResult r = renderer.render(p, views[v].camera, run.settings);
            run.device.push_back(frameMs(r));
            run.wall.push_back(r.wallMilliseconds);
            run.iterations.insert(run.iterations.end(), r.iterations.begin(), r.iterations.end());
            run.errors.push_back(imageError(references[v], r.image));
            run.uploadedBytes = 0;
            for (const UploadedResource& u : renderer.lastUploads()) run.uploadedBytes += (long long)u.bytes;
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
// a setting already there is an InputError (appending would give it twice).
std::vector<std::pair<double, double>> pendingSettings(const SweepOptions& o, const std::string& dataset,
                                                       const fs::path& csv) {
    std::set<std::string> done;
    for (const SweepRow& r : readSweepCsv(csv)) done.insert(r.key());
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

ClassifiedVolume loadClassified(const SweepOptions& o, const std::string& dataset, std::size_t settings) {
    StageClock loading;
    const Volume volume = loadVolume(o.input, o.raw);
    const double loadSeconds = loading.stop("load").seconds;
    ClassifyParams params;
    params.transferFunction = loadTransferFunction(o.transferFunction);
    params.normals = o.shading;
    StageClock classifying;
    ClassifiedVolume classified = classify(volume, params);
    std::fprintf(stderr, "%s: %dx%dx%d voxels, load %.2f s, classify %.2f s, %zu settings to run\n",
                 dataset.c_str(), volume.grid.dims.x, volume.grid.dims.y, volume.grid.dims.z, loadSeconds,
                 classifying.stop("classify").seconds, settings);
    return classified;
}

}  // namespace

int runSweep(const SweepOptions& o) {
    o.validate();
    const std::string dataset = o.datasetName();
    const fs::path csv = o.outDir / "sweep.csv";
    const fs::path images = imagesDir(o.outDir, dataset);

    const std::vector<std::pair<double, double>> settings = pendingSettings(o, dataset, csv);

    // Load and classify once: the classification does not depend on the thresholds.
    PreparedVolume p;
    p.classified = loadClassified(o, dataset, settings.size());
    p.meta.source = o.input.string();
    fs::create_directories(images);

    VulkanContext context(VulkanOptions{o.device, false});
    VulkanRenderer renderer(context);
    RenderSettings base;
    base.stepVoxels = o.stepVoxels;
    base.shading = o.shading;
    base.trilinear = o.trilinear;
    const std::vector<View> views = orbit(o, p.classified.grid);

    // The reference: the primitive caster at T_o = T_a = 0 (it reads no regions or fields), once per view.
    std::vector<Image> references;
    std::map<double, Image> elevationZero;
    for (const View& v : views) {
        references.push_back(renderer.render(p, v.camera, base).image);
        if (v.elevation == 0) elevationZero[v.azimuth] = references.back();
    }
    writeImage(images / "reference.png", references.front());
    if (!o.peersDir.empty()) {
        const nlohmann::json peers = comparePeers(o.peersDir, elevationZero);
        writeFileAtomically(o.outDir / ("peers_" + dataset + ".json"),
                            [&](std::ostream& s) { s << peers.dump(2) << '\n'; });
    }
    if (settings.empty()) return 0;

    const unsigned kinds = fieldsFor(o.casters);
    ProgressBar bar("sweep " + dataset, settings.size() * o.casters.size() * views.size());
    std::set<Caster> warmed;
    for (const auto& [to, ta] : settings) {
        SweepRow row;
        row.dataset = dataset;
        row.opacityThreshold = to;
        row.angleThreshold = ta;
        row.views = int(views.size());
        row.width = o.width;
        row.height = o.height;
        prepareSetting(p, SegmentationParams{to, ta, o.shading, o.trilinear}, kinds, row);
        std::vector<CasterRun> runs;
        for (Caster c : o.casters) {
            runs.push_back({});
            runs.back().settings = base;
            runs.back().settings.caster = c;
            if (warmed.insert(c).second) renderer.render(p, views.front().camera, runs.back().settings);  // warm-up
        }
        renderSetting(renderer, p, views, references, runs, row, images, bar);
        std::vector<SweepRow> rows;
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
