#include "preprocess/pipeline/prepare.h"

#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <bit>
#include <chrono>
#include <sstream>

#include "io/prepared_file.h"
#include "tools/progress.h"
#include "preprocess/fields/build_fields.h"
#include "render/ray_probe.h"
#include "preprocess/segment/segment.h"

namespace vr {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

double processCpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(u.ru_utime) + seconds(u.ru_stime);
}

// One stage of the pipeline: a progress bar (one step unless told), timed until done().
class Stage {
public:
    Stage(std::vector<StageTime>& stages, std::string name, std::size_t steps = 1)
        : stages_(stages), name_(std::move(name)), bar_(name_, steps) {}
    void advance() { bar_.advance(); }
    void done() {
        stages_.push_back(clock_.stop(name_));
        bar_.finish();
    }

private:
    std::vector<StageTime>& stages_;
    std::string name_;
    ProgressBar bar_;
    StageClock clock_;
};

// Means of the N distances get(element) gives, over a field (a vector or an ExtentField), in parallel: one pass,
// each element read (an ExtentField's box decoded) once.
template <std::size_t N, typename Field, typename Get>
std::array<double, N> meansOf(const Field& v, Get get) {
    using Sums = std::array<double, N>;
    if (v.empty()) return {};
    Sums sum = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, v.size()), Sums{},
        [&](const tbb::blocked_range<std::size_t>& r, Sums s) {
            std::array<uint64_t, N> local{};  // exact: at most 255 per voxel
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                const auto x = get(v[i]);
                for (std::size_t a = 0; a < N; ++a) local[a] += x[a];
            }
            for (std::size_t a = 0; a < N; ++a) s[a] += double(local[a]);
            return s;
        },
        [](Sums a, const Sums& b) {
            for (std::size_t i = 0; i < N; ++i) a[i] += b[i];
            return a;
        });
    for (double& m : sum) m /= double(v.size());
    return sum;
}

double meanOf(const std::vector<uint8_t>& distances) {
    return meansOf<1>(distances, [](uint8_t d) { return std::array<uint8_t, 1>{d}; })[0];
}

template <typename T>
std::size_t bytesOf(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

}  // namespace

DistanceFields buildTimedFields(const Regions& regions, unsigned kinds, ExtentCode eacdCode,
                                std::vector<StageTime>& stages) {
    // One call builds them all, sharing the axial runs and the ACDs: each field is timed from the end of the one
    // before (ACD first, then PC from the ACDs, then EACD).
    const unsigned built = (kinds & kFieldEACD ? kinds | kFieldACD : kinds) & (kFieldPC | kFieldACD | kFieldEACD);
    ProgressBar bar("fields", std::popcount(built));
    StageClock clock;
    // The EACD is written in eacdCode as it is built: memory, file and device then hold the same bytes.
    DistanceFields f = buildFields(regions, kinds, eacdCode, [&](FieldKind kind) {
        stages.push_back(clock.stop(kind == kFieldPC ? "pc" : kind == kFieldACD ? "acd" : "eacd"));
        bar.advance();
        clock = StageClock();
    });
    bar.finish();
    return f;
}

StageClock::StageClock() : wall_(std::chrono::steady_clock::now()), cpu_(processCpuSeconds()) {}

StageTime StageClock::stop(std::string stage) const {
    return {std::move(stage), std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_).count(),
            processCpuSeconds() - cpu_};
}

std::string classificationText(const ClassifyParams& params) {
    if (params.transferFunction) return params.transferFunction->json;
    std::ostringstream s;
    s.precision(17);
    s << "iso";
    for (std::size_t i = 0; i < params.isoContours.size(); ++i) {
        const IsoContour& c = params.isoContours[i];
        s << (i ? "; " : " ") << c.value << "," << c.width << "," << c.strength;
    }
    return s.str();
}

json preparedStatistics(const PreparedVolume& p, const std::vector<StageTime>& stages) {
    const std::size_t voxels = p.classified.grid.voxels();
    json s;
    s["voxels"] = voxels;
    s["regions"] = p.regions.count;
    s["meanRegionSize"] = p.regions.count ? double(voxels) / p.regions.count : 0.0;

    json leaps = json::object();
    const DistanceFields& f = p.fields;
    if (f.hasPC()) leaps["pcMeanRadius"] = meanOf(f.pc);
    if (f.hasACD()) {
        json edges = json::array();
        for (int o = 0; o < kOctants; ++o) edges.push_back(meanOf(f.acd[o]));
        leaps["acdMeanEdge"] = edges;
    }
    if (f.hasEACD()) {
        json extents = json::array();
        for (int o = 0; o < kOctants; ++o) extents.push_back(meansOf<3>(f.eacd[o], [](const Extents& e) { return e; }));
        leaps["eacdMeanExtent"] = extents;
    }
    s["leaps"] = leaps;
    if (json probe = rayProbe(p); !probe.is_null()) s["rayProbe"] = std::move(probe);

    std::size_t acd = 0, eacd = 0;
    for (int o = 0; o < kOctants; ++o) {
        acd += bytesOf(f.acd[o]);
        eacd += f.eacd[o].bytes();
    }
    s["bytes"] = {{"sigma", bytesOf(p.classified.sigma)}, {"colour", bytesOf(p.classified.colour)},
                  {"normal", bytesOf(p.classified.normal)}, {"labels", bytesOf(p.regions.label)},
                  {"pc", bytesOf(f.pc)}, {"acd", acd}, {"eacd", eacd}};
    s["eacdCode"] = extentCodeName(f.eacdCode());
    json seconds = json::object(), cpuSeconds = json::object();
    for (const StageTime& t : stages) {
        seconds[t.stage] = t.seconds;
        cpuSeconds[t.stage] = t.cpuSeconds;
    }
    s["seconds"] = seconds;
    s["cpuSeconds"] = cpuSeconds;
    return s;
}

PrepareResult prepareVolume(const fs::path& input, const PrepareOptions& options) {
    PrepareResult r;
    PreparedVolume& p = r.prepared;
    Stage load(r.stages, "load");
    Volume volume = loadVolume(input, options.raw);
    load.done();
    Stage classifying(r.stages, "classify");
    p.classified = classify(volume, options.classify);
    classifying.done();
    volume = {};  // the scalars are not needed any more: free them before the big stages
    Stage segmenting(r.stages, "segment");
    p.regions = segment(p.classified, options.segmentation);
    segmenting.done();
    p.fields = buildTimedFields(p.regions, options.fields, options.eacdCode, r.stages);

    p.meta.source = input.string();
    p.meta.classification = classificationText(options.classify);
    p.meta.segmentation = options.segmentation;
    p.meta.distanceCap = kDistanceCap;
    p.meta.statistics = preparedStatistics(p, r.stages);
    return r;
}

PrepareResult prepareFile(const fs::path& input, const fs::path& output, const PrepareOptions& options) {
    PrepareResult r = prepareVolume(input, options);
    Stage write(r.stages, "write");
    writePrepared(output, r.prepared);
    write.done();
    r.fileBytes = fs::file_size(output);
    return r;
}

}  // namespace vr
