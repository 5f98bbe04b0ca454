#include "sweep/run_sweep.h"

#include <cstdio>
#include <map>
#include <memory>
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

// Every view of one caster: times, work per ray, error against the references; view 0's images are written.
SweepRow renderCaster(VulkanRenderer& renderer, const PreparedVolume& p, const std::vector<View>& views,
                      const std::vector<Image>& references, RenderSettings settings, SweepRow row,
                      const fs::path& images, ProgressBar& bar) {
    row.caster = std::string(casterName(settings.caster));
    std::vector<double> device, wall;
    std::vector<uint32_t> iterations;
    std::vector<ImageError> errors;
    for (std::size_t v = 0; v < views.size(); ++v) {
        RenderResult r = renderer.render(p, views[v].camera, settings);
        device.push_back(frameMs(r));
        wall.push_back(r.wallMilliseconds);
        iterations.insert(iterations.end(), r.iterations.begin(), r.iterations.end());
        errors.push_back(imageError(references[v], r.image));
        if (v == 0) {
            writeImage(images / imageName(row.caster, row.opacityThreshold, row.angleThreshold, false), r.image);
            writeImage(images / imageName(row.caster, row.opacityThreshold, row.angleThreshold, true),
                       errorMap(references[v], r.image));
        }
        bar.advance();
    }
    row.deviceMsMedian = median(device);
    row.deviceMsP95 = percentile(device, 0.95);
    row.wallMsMedian = median(wall);
    double sum = 0;
    for (uint32_t i : iterations) sum += i;
    row.iterationsMean = iterations.empty() ? 0 : sum / double(iterations.size());
    row.iterationsP95 = percentile(iterations, 0.95);
    row.iterationsMax = percentile(iterations, 1.0);
    row.fieldBytes = fieldBytes(p.fields, settings.caster);
    row.uploadedBytes = 0;
    for (const UploadedResource& u : renderer.lastUploads()) row.uploadedBytes += (long long)u.bytes;
    row.error = summarize(errors);
    return row;
}

}  // namespace

int runSweep(const SweepOptions& o) {
    o.validate();
    const std::string dataset = o.datasetName();
    fs::create_directories(o.outDir);
    const fs::path csv = o.outDir / "sweep.csv";
    const fs::path images = imagesDir(o.outDir, dataset);
    fs::create_directories(images);

    std::set<std::string> done;
    for (const SweepRow& r : readSweepCsv(csv)) done.insert(r.key());
    std::vector<std::pair<double, double>> settings;
    for (double to : o.opacityThresholds)
        for (double ta : o.angleThresholds) {
            bool all = o.resume;
            for (Caster c : o.casters) all = all && done.count(rowKey(dataset, to, ta, std::string(casterName(c))));
            if (!all) settings.emplace_back(to, ta);
        }
    if (!o.resume && !done.empty())
        for (const auto& [to, ta] : settings) {
            if (done.count(rowKey(dataset, to, ta, "primitive")))
                throw fileError(csv.string(), "already holds rows of " + dataset + " at T_o " + thresholdText(to) +
                                                  ", T_a " + thresholdText(ta) + ": pass --resume or another -o");
        }

    // Load and classify once: the classification does not depend on the thresholds.
    PreparedVolume p;
    {
        StageClock loading;
        const Volume volume = loadVolume(o.input, o.raw);
        const double loadSeconds = loading.stop("load").seconds;
        ClassifyParams params;
        params.transferFunction = loadTransferFunction(o.transferFunction);
        params.normals = o.shading;
        StageClock classifying;
        p.classified = classify(volume, params);
        std::fprintf(stderr, "%s: %dx%dx%d voxels, load %.2f s, classify %.2f s, %zu settings to run\n",
                     dataset.c_str(), volume.grid.dims.x, volume.grid.dims.y, volume.grid.dims.z, loadSeconds,
                     classifying.stop("classify").seconds, settings.size());
    }
    p.meta.source = o.input.string();

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
        std::vector<SweepRow> rows;
        for (Caster c : o.casters) {
            RenderSettings s = base;
            s.caster = c;
            if (warmed.insert(c).second) renderer.render(p, views.front().camera, s);  // pipeline build, caches
            rows.push_back(renderCaster(renderer, p, views, references, s, row, images, bar));
        }
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
