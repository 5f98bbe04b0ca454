// --caster auto against the fixed casters: on every raw dataset of the shared MANIFEST.tsv and the
// synthetic phantoms, each fixed caster's time for a few views (device ms of the renders, sum over views of the
// median over repeats, plus the wall ms of uploading its field once) with its mean loop iterations per pixel,
// auto's one choice for the views (render/caster_choice.h, from the ray probe volprep stores) and its ratio to
// the fastest fixed caster (target: at most 1.10), the run-to-run spread of the fastest fixed caster (the noise
// the ratio sits in), and a least-squares fit of the choice model's constants to the renders (re-run it when the
// shader loop or the device changes; --write-calibration FILE stores it for volrender --calibration), and how the
// primitive caster's iteration time grows with the scalars' bytes, on the cranium CT resampled to larger sizes
// (--growth-sizes; the calibration's iterationGrowth). Prints Markdown tables. --short: one tiny dataset at 64x64
// (CTest).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <limits>
#include <map>
#include <string>

#include "bench_checks.h"
#include "datasets/phantoms.h"
#include "io/caster_calibration_file.h"
#include "resampled_volume.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "support/datasets.h"
#include "support/load_dataset.h"
#include "sweep/order_statistics.h"
#include "render/caster_choice.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace vr;

constexpr double kTarget = 1.10;  // auto within 10 % of the fastest fixed caster
constexpr int kRowsToFit = 10;
// The clinical-size CT of the whole-process benchmark and sizes on the way to it (5 unknowns: fewer rows leave the
// ray's ns ill-determined).
const std::string kDefaultGrowthSizes = "256x256x128,512x512x256,512x512x512,512x512x1024";
const Caster kFixed[] = {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD};

struct Scene {
    std::string name;
    std::size_t voxels;
    std::function<Volume()> load;  // loaded when its turn comes
    fs::path tf;
};


// Orthographic views from three sides and one perspective view: the octants and projections auto must handle.
std::vector<ViewParams> benchViews(int size, int count) {
    std::vector<ViewParams> all;
    for (auto [projection, azimuth, elevation] :
         {std::tuple{Projection::Orthographic, 30.0, 20.0}, std::tuple{Projection::Perspective, 120.0, 15.0},
          std::tuple{Projection::Orthographic, 200.0, -25.0}, std::tuple{Projection::Orthographic, 0.0, 0.0}}) {
        ViewParams v;
        v.projection = projection;
        v.azimuthDeg = azimuth;
        v.elevationDeg = elevation;
        v.width = v.height = size;
        all.push_back(v);
    }
    all.resize(std::min(all.size(), std::size_t(count)));
    return all;
}

// The real datasets whose names start with one of `prefixes` (all when empty) and the phantoms (int16 shells
// with the CT transfer function; the uint8 phantoms with the simulation one), smallest first.
std::vector<Scene> scenes(const std::vector<std::string>& prefixes, int phantomSize) {
    auto wanted = [&](const std::string& name) {
        if (prefixes.empty()) return true;
        for (const std::string& p : prefixes)
            if (name.rfind(p, 0) == 0) return true;
        return false;
    };
    std::vector<Scene> out;
    const fs::path dir = test::datasetsDir();
    for (const test::DatasetEntry& e : test::rawManifest()) {
        if (!wanted(e.file)) continue;
        RawOptions raw;
        raw.dims = e.dims;
        raw.type = e.type;
        raw.spacing = e.spacing;
        out.push_back({e.file.substr(0, e.file.find(".raw")), voxelCount(e.dims),
                       [=] { return loadVolume(dir / e.file, raw); }, dir / e.tf});
    }
    const Vec3i n{phantomSize, phantomSize, phantomSize};
    const fs::path ct = dir / "cranium_ct.tf.json", sim = dir / "sim.tf.json";
    const std::pair<std::string, std::function<Volume()>> phantoms[] = {
        {"phantom_shells", [=] { return shellsPhantom(n); }},
        {"phantom_engine", [=] { return enginePhantom(n); }},
        {"phantom_ramp", [=] { return rampPhantom(n, 0); }},
        {"phantom_constant", [=] { return constantPhantom(n, 100); }},
        {"phantom_checkerboard", [=] { return checkerboardPhantom(n); }},
        {"phantom_noise", [=] { return noisePhantom(n, 7); }}};
    for (const auto& [name, make] : phantoms)
        if (wanted(name)) out.push_back({name, voxelCount(n), make, name == "phantom_shells" ? ct : sim});
    std::stable_sort(out.begin(), out.end(), [](const Scene& a, const Scene& b) { return a.voxels < b.voxels; });
    return out;
}

// Segments and builds every field at one setting (classified once per scene), with the statistics and the ray
// probe volprep would store (timed: the probe's cost is part of every preparation).
const PreparedVolume& prepareSetting(StagedPreparation& staged, PrepareOptions& options, double to, double ta,
                                     StageTime& statistics) {
    options.segmentation = {to, ta, true, false};
    staged.prepare(options);
    const StageClock clock;
    const PreparedVolume& p = staged.withStatistics();
    statistics = clock.stop("statistics");
    return p;
}

constexpr uint32_t kIterationMask = 0x3fffffffu;  // the renderer's flags sit above the count

struct Timings {
    // [caster][view][repeat]: device ms, and mean loop iterations per pixel (the same every repeat).
    std::map<Caster, std::vector<std::vector<double>>> ms;
    std::map<Caster, std::vector<double>> iterations;
    std::map<Caster, double> fieldBytes;     // device bytes of the caster's field for the views
    double uploadNsPerByte = 0;              // wall time of uploading a field byte (median)
    std::map<Caster, double> fieldUploadMs;  // fieldBytes x uploadNsPerByte
    CasterChoice chosen;                     // auto's one choice for all the views, as volrender makes it
    std::vector<std::string> viewEstimates;  // auto's estimates for each view alone (--explain)
};

// Wall ms and bytes of uploading what one caster needs for the views: the scalars, the transfer table, its field.
std::pair<double, double> upload(VulkanRenderer& renderer, const PreparedVolume& p, Caster c, unsigned octants) {
    const StageClock clock;
    const GpuVolume volume = renderer.upload(p, {{c}, octants});
    return {1e3 * clock.stop("upload").seconds, double(volume.uploadedBytes())};
}

// Every view `repeats` times, the fixed casters taking turns within a view (in a rotating order) so that a busy
// machine slows them alike; one warm-up frame per caster first. Auto's choice is made once for all the views
// (their octants, one upload shared by them), and its time IS that of the caster it chose (the choice is a few
// operations on the statistics): rendering it again would only add the machine's noise to the comparison.
Timings measure(VulkanRenderer& renderer, const PreparedVolume& p, const std::vector<ViewParams>& views, int repeats,
                double step) {
    Timings t;
    RenderSettings s;
    s.stepVoxels = step;
    std::vector<Camera> cameras;
    GpuVolumeContents contents{{std::begin(kFixed), std::end(kFixed)}, 0};
    CasterDemand demand{0, {}, (long long)views.front().width * views.front().height, step,
                        scalarBytesOnDevice(p.grid(), p.scalars.sourceType)};
    for (const ViewParams& v : views) {
        cameras.push_back(Camera::fit(p.grid(), v));
        demand.addView(cameras.back());
    }
    contents.octants = demand.octants;
    const FieldBytes fieldBytes = fieldBytesOf(p.fields);
    t.chosen = chooseCaster(p.meta.rayProbe, fieldBytes, demand);
    for (unsigned classes : demand.views) {
        CasterDemand one = demand;
        one.views = {classes};
        t.viewEstimates.push_back(chooseCaster(p.meta.rayProbe, fieldBytes, one).reason);
    }

    // The fields' uploads: what a caster adds to the scalars and the table every caster uploads. On a
    // shared machine one upload's wall time scatters more than a small field takes, so the rate is measured on the
    // biggest fields (ACD, EACD), each timed back to back with primitive's upload, and the median rate over them
    // and the repeats prices every field's exact bytes.
    std::vector<double> rates;  // ns per field byte
    for (int r = 0; r < repeats; ++r)
        for (Caster c : {Caster::ACD, Caster::EACD}) {
            const auto [primitiveMs, primitiveBytes] = upload(renderer, p, Caster::Primitive, contents.octants);
            const auto [ms, bytes] = upload(renderer, p, c, contents.octants);
            t.fieldBytes[c] = bytes - primitiveBytes;
            rates.push_back(1e6 * (ms - primitiveMs) / t.fieldBytes[c]);
        }
    t.uploadNsPerByte = std::max(0.0, median(rates));
    t.fieldBytes[Caster::Primitive] = 0;
    t.fieldBytes[Caster::PC] = double(p.fields.pc.size());  // one byte a voxel for every direction
    for (Caster c : kFixed) t.fieldUploadMs[c] = 1e-6 * t.uploadNsPerByte * t.fieldBytes[c];

    const GpuVolume volume = renderer.upload(p, contents);  // once for every caster and view
    for (Caster c : kFixed) {
        s.caster = c;
        renderer.render(volume, cameras.front(), s);
        t.ms[c].assign(views.size(), {});
    }
    int turn = 0;
    for (int r = 0; r < repeats; ++r)
        for (std::size_t i = 0; i < views.size(); ++i, ++turn)
            for (int k = 0; k < 4; ++k) {
                s.caster = kFixed[(k + turn) % 4];
                const RenderResult result = renderer.render(volume, cameras[i], s);
                t.ms[s.caster][i].push_back(result.deviceMilliseconds);
                if (r > 0) continue;
                double sum = 0;
                for (uint32_t n : result.iterations) sum += n & kIterationMask;
                t.iterations[s.caster].push_back(sum / double(result.iterations.size()));
            }
    return t;
}

// A blocks MIP iteration's device time over a primitive one's on the views, trilinear as users render MIP: (blocks
// ms / its iterations) / (primitive ms / its iterations), ms the sum over the views of the median over repeats. The
// calibration's blocksIterationRatio is the median over the scenes.
double blocksIterationRatio(VulkanRenderer& renderer, const PreparedVolume& p, const std::vector<ViewParams>& views,
                            int repeats, double step) {
    RenderSettings s;
    s.stepVoxels = step;
    s.blend = Blend::MIP;
    s.trilinear = true;
    const GpuVolume volume = renderer.upload(p, {{Caster::Primitive, Caster::Blocks}, 0});
    std::map<Caster, double> nsPerIteration;
    for (Caster c : {Caster::Primitive, Caster::Blocks}) {
        s.caster = c;
        renderer.render(volume, Camera::fit(p.grid(), views.front()), s);  // warm-up
        double ms = 0, iterations = 0;
        for (const ViewParams& v : views) {
            const Camera camera = Camera::fit(p.grid(), v);
            std::vector<double> times;
            RenderResult r;
            for (int k = 0; k < repeats; ++k) {
                r = renderer.render(volume, camera, s);
                times.push_back(r.deviceMilliseconds);
            }
            ms += median(times);
            for (uint32_t n : r.iterations) iterations += n & kIterationMask;  // the same every repeat
        }
        nsPerIteration[c] = 1e6 * ms / iterations;
    }
    return nsPerIteration[Caster::Blocks] / nsPerIteration[Caster::Primitive];
}

// A caster's time for the views: the sum over views of the median over repeats.
double total(const std::vector<std::vector<double>>& perView) {
    double sum = 0;
    for (const auto& repeats : perView) sum += median(repeats);
    return sum;
}

// Run-to-run spread of a caster: (max - min) / median of its per-repeat sums over the views.
double spread(const std::vector<std::vector<double>>& perView) {
    std::vector<double> sums(perView.front().size(), 0.0);
    for (const auto& repeats : perView)
        for (std::size_t r = 0; r < repeats.size(); ++r) sums[r] += repeats[r];
    const auto [lo, hi] = std::minmax_element(sums.begin(), sums.end());
    return (*hi - *lo) / median(sums);
}

// One render's time against the model's terms: ns per pixel = ray + iterations x (the caster's ns per iteration).
struct RenderSample {
    Caster caster;
    double iterations;  // per pixel
    double nsPerPixel;
};

// Least squares of the relative error of ns per pixel = rayNs + iterations x iterationNs[caster] over the
// renders (normal equations of 5 unknowns: the ray's ns, then one per caster in kFixed order).
std::array<double, 5> fitModel(const std::vector<RenderSample>& samples) {
    constexpr int n = 5;
    std::array<std::array<double, n + 1>, n> m{};  // [A^T A | A^T b]
    for (const RenderSample& r : samples) {
        std::array<double, n> row{1, 0, 0, 0, 0};
        row[1 + int(r.caster)] = r.iterations;
        for (double& x : row) x /= r.nsPerPixel;  // relative: each render weighs alike
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) m[i][j] += row[i] * row[j];
            m[i][n] += row[i];
        }
    }
    for (int i = 0; i < n; ++i)  // Gauss-Jordan; the matrix is symmetric positive definite
        for (int k = 0; k < n; ++k) {
            if (k == i) continue;
            const double f = m[k][i] / m[i][i];
            for (int j = i; j <= n; ++j) m[k][j] -= f * m[i][j];
        }
    std::array<double, n> x{};
    for (int i = 0; i < n; ++i) x[i] = m[i][n] / m[i][i];
    return x;
}

// The driver's name and version (VK_KHR_driver_properties: "Mesa 22.3.6" where VkPhysicalDeviceProperties has a
// vendor's number), or its raw version number where the device lacks the extension.
std::string driverVersion(const vk::raii::PhysicalDevice& device) {
    for (const vk::ExtensionProperties& e : device.enumerateDeviceExtensionProperties())
        if (std::string_view(e.extensionName) == VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME) {
            using Driver = vk::PhysicalDeviceDriverProperties;
            const auto chain = device.getProperties2<vk::PhysicalDeviceProperties2, Driver>();
            const Driver& driver = chain.get<Driver>();
            return std::string(driver.driverName.data()) + " " + driver.driverInfo.data();
        }
    return std::to_string(device.getProperties().driverVersion);
}

// The Vulkan device the renders ran on, and now: volrender matches a calibration file to its device by name.
void describeDevice(const VulkanContext& context, CasterCalibration& c) {
    c.deviceName = context.info().name;
    c.driverVersion = driverVersion(context.physicalDevice());
    const std::time_t now = std::time(nullptr);
    char utc[32];
    std::strftime(utc, sizeof utc, "%FT%TZ", std::gmtime(&now));
    c.measuredAt = utc;
}

// Whether the prepared volume holds the field caster c needs.
bool hasFieldOf(const PreparedVolume& p, Caster c) {
    switch (c) {
        case Caster::Primitive: return true;
        case Caster::PC: return p.fields.hasPC();
        case Caster::ACD: return p.fields.hasACD();
        case Caster::EACD: return p.fields.hasEACD();
        case Caster::Blocks: return true;  // built from the scalars
        case Caster::Hier: return !p.fields.hier.empty();
    }
    return false;
}

// The primitive caster's time per iteration on one volume size: the views' device ns per pixel (median over the
// repeats) less the ray's ns, over the mean iterations per pixel.
struct SizeSample {
    double scalarBytes;
    double iterations;  // per pixel
    double iterationNs;
};

SizeSample primitiveOnSize(VulkanRenderer& renderer, const PreparedVolume& p, const std::vector<ViewParams>& views,
                           int repeats, double step, double rayNs) {
    RenderSettings s;
    s.stepVoxels = step;
    std::vector<Camera> cameras;
    unsigned octants = 0;
    for (const ViewParams& v : views) {
        cameras.push_back(Camera::fit(p.grid(), v));
        octants |= viewOctants(cameras.back());
    }
    const GpuVolume volume = renderer.upload(p, {{Caster::Primitive}, octants});
    renderer.render(volume, cameras.front(), s);  // warm-up
    double nsPerPixel = 0, iterations = 0;
    for (const Camera& camera : cameras) {
        std::vector<double> ms;
        for (int r = 0; r < repeats; ++r) {
            const RenderResult result = renderer.render(volume, camera, s);
            ms.push_back(result.deviceMilliseconds);
            if (r > 0) continue;
            double sum = 0;
            for (uint32_t n : result.iterations) sum += n & kIterationMask;
            iterations += sum / double(result.iterations.size()) / double(cameras.size());
        }
        nsPerPixel += median(ms) * 1e6 / double(camera.width * camera.height) / double(cameras.size());
    }
    return {scalarBytesOnDevice(p.grid(), p.scalars.sourceType), iterations, (nsPerPixel - rayNs) / iterations};
}

// The growth that fits the samples (smallest first) best: for each sample's bytes as the knee, the in-cache time
// is the mean of those at or below it and the growth per doubling beyond it a least-squares slope of the times
// over it against log2 of the bytes over the knee; the knee with the least squared error wins.
IterationGrowth fitGrowth(const std::vector<SizeSample>& samples) {
    IterationGrowth best;
    double leastError = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < samples.size(); ++k) {
        double inCache = 0;
        for (std::size_t i = 0; i <= k; ++i) inCache += samples[i].iterationNs / double(k + 1);
        double xy = 0, xx = 0;
        for (std::size_t i = k + 1; i < samples.size(); ++i) {
            const double x = std::log2(samples[i].scalarBytes / samples[k].scalarBytes);
            xy += x * (samples[i].iterationNs / inCache - 1);
            xx += x * x;
        }
        const IterationGrowth g{samples[k].scalarBytes, xx > 0 ? std::max(0.0, xy / xx) : 0};
        double error = 0;
        for (const SizeSample& sample : samples)
            error += std::pow(sample.iterationNs / inCache - iterationScale(g, sample.scalarBytes), 2);
        if (error < leastError) leastError = error, best = g;
    }
    return best;
}

// Each size's primitive renders, printed as a table, and the growth fitted to them.
IterationGrowth measureGrowth(bench::Checks& checks, VulkanRenderer& renderer, const std::vector<Vec3i>& sizes,
                              const std::vector<ViewParams>& views, int repeats, double step, double rayNs) {
    const test::DatasetEntry e = test::rawDataset("cranium_ct");
    const Volume source = test::loadDataset(e);
    PrepareOptions options;
    options.classify.transferFunction = test::datasetTransferFunction(e.tf);
    options.fields = 0;
    std::printf("\nThe primitive caster's time per iteration against the scalars' bytes: %s resampled (noise of 20), "
                "the same views, ns per iteration = (device ns per pixel - ray %.0f) / iterations per pixel.\n\n"
                "| size | scalar MB | iterations per pixel | ns per iteration |\n|---|---:|---:|---:|\n",
                e.file.c_str(), rayNs);
    std::vector<SizeSample> samples;
    for (const Vec3i& dims : sizes) {
        StagedPreparation staged(bench::withNoise(bench::resample(source, dims), 20, 1));
        samples.push_back(primitiveOnSize(renderer, staged.prepare(options), views, repeats, step, rayNs));
        const SizeSample& sample = samples.back();
        std::printf("| %dx%dx%d | %.0f | %.1f | %.1f |\n", dims.x, dims.y, dims.z, sample.scalarBytes / 1e6,
                    sample.iterations, sample.iterationNs);
        checks.expect(sample.iterations > 0 && std::isfinite(sample.iterationNs) && sample.iterationNs > 0,
                      "%dx%dx%d: %g iterations per pixel at %g ns each, not both > 0", dims.x, dims.y, dims.z,
                      sample.iterations, sample.iterationNs);
        std::fflush(stdout);
    }
    const IterationGrowth g = fitGrowth(samples);
    std::printf("\nGrowth (a calibration's iterationGrowth): %.2f per doubling of the scalars' bytes beyond %.0f MB.\n",
                g.perDoubling, g.cachedBytes / 1e6);
    return g;
}

// What a row of the table says: the regions partition the voxels; every fixed caster rendered every view in a
// positive time and looped in it; a field costs bytes to upload (primitive has none); auto chose a caster whose field
// the volume has, for a reason; and its ratio to the fastest is a ratio of times. (Whether auto is within the target
// is what the table measures, not a check: one repeat on a shared machine scatters by more than the target's 10 %.)
void checkRow(bench::Checks& checks, const std::string& row, const PreparedVolume& p, std::size_t voxels,
              const Timings& t, const std::map<Caster, double>& renders, double ratio, double spread) {
    checks.expect(p.regions.count >= 1 && p.regions.count <= voxels, "%s: %u regions, not within 1..%zu voxels",
                  row.c_str(), p.regions.count, voxels);
    for (Caster c : kFixed) {
        const char* name = casterName(c).data();
        checks.expect(renders.at(c) > 0, "%s: %s renders took %g device ms, not > 0", row.c_str(), name,
                      renders.at(c));
        for (std::size_t v = 0; v < t.iterations.at(c).size(); ++v)
            checks.expect(t.iterations.at(c)[v] > 0, "%s: %s took %g iterations per pixel in view %zu, not > 0",
                          row.c_str(), name, t.iterations.at(c)[v], v);
        checks.expect(c == Caster::Primitive ? t.fieldBytes.at(c) == 0 : t.fieldBytes.at(c) > 0,
                      "%s: %s's field is %g bytes", row.c_str(), name, t.fieldBytes.at(c));
        checks.expect(std::isfinite(t.fieldUploadMs.at(c)) && t.fieldUploadMs.at(c) >= 0,
                      "%s: %s's field upload of %g ms", row.c_str(), name, t.fieldUploadMs.at(c));
    }
    checks.expect(hasFieldOf(p, t.chosen.caster), "%s: auto chose %s, whose field the volume lacks", row.c_str(),
                  casterName(t.chosen.caster).data());
    checks.expect(!t.chosen.reason.empty(), "%s: auto's choice gives no reason", row.c_str());
    checks.expect(std::isfinite(ratio) && ratio >= 1, "%s: auto / fastest is %g, not a ratio >= 1", row.c_str(),
                  ratio);
    checks.expect(std::isfinite(spread) && spread >= 0, "%s: spread %g", row.c_str(), spread);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"--caster auto against the fixed casters: median device ms over a few views on every shared "
                 "dataset and the phantoms, and auto's ratio to the fastest fixed caster"};
    bool shortMode = false, explain = false;
    int size = 256, viewCount = 4, repeats = 3, phantomSize = 128, device = -1;
    double step = 0.5;
    std::vector<double> to{0, 0.02}, ta{0, 10};
    std::vector<std::string> datasets;
    std::string calibrationFile;
    std::vector<std::string> growthSizes;
    bool growthOnly = false;
    app.add_flag("--short", shortMode, "one tiny dataset (vtk_headmr), 64x64, 2 views, once: a few seconds (CTest)");
    app.add_flag("--explain", explain, "print auto's estimates for every view below each row");
    app.add_option("--datasets", datasets, "dataset name prefixes (MANIFEST.tsv files, phantom_NAME); default all")
        ->delimiter(',');
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", viewCount, "views (1..4: ortho, persp, ortho, ortho)")
        ->check(CLI::Range(1, 4))
        ->capture_default_str();
    app.add_option("--repeats", repeats, "renders of every view per caster")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--phantom-size", phantomSize, "edge of the phantoms")->capture_default_str();
    app.add_option("--to", to, "T_o per setting")->delimiter(',')->capture_default_str();
    app.add_option("--ta", ta, "T_a per setting (as many as --to), degrees")->delimiter(',')->capture_default_str();
    app.add_option("--step", step, "step in voxels")->capture_default_str();
    app.add_option("--device", device, "Vulkan device index");
    app.add_option("--write-calibration", calibrationFile,
                   "write the fit, the upload rate and the device as a calibration file for volrender "
                   "--calibration (needs 10 rows or more)");
    app.add_option("--growth-sizes", growthSizes,
                   "sizes XxYxZ, smallest first, of the cranium CT resampled with noise, primitive renders only: "
                   "how an iteration's time grows with the scalars' bytes (a calibration's iterationGrowth; 3 or "
                   "more; with --write-calibration the default is " + kDefaultGrowthSizes + ")")
        ->delimiter(',');
    app.add_flag("--growth-only", growthOnly, "only the --growth-sizes table: no dataset rows, no calibration");
    CLI11_PARSE(app, argc, argv);
    if (!calibrationFile.empty() && growthSizes.empty()) growthSizes = CLI::detail::split(kDefaultGrowthSizes, ',');
    std::vector<Vec3i> growthDims;
    for (const std::string& text : growthSizes) {
        Vec3i dims;
        char tail = 0;
        if (std::sscanf(text.c_str(), "%dx%dx%d%c", &dims.x, &dims.y, &dims.z, &tail) != 3 || dims.x < 2 ||
            dims.y < 2 || dims.z < 2) {
            std::fprintf(stderr, "auto_caster_bench: --growth-sizes: '%s' is not XxYxZ of 2 voxels or more each\n",
                         text.c_str());
            return 2;
        }
        growthDims.push_back(dims);
    }
    if (growthOnly && (growthDims.empty() || !calibrationFile.empty())) {
        std::fprintf(stderr, "auto_caster_bench: --growth-only needs --growth-sizes and writes no calibration\n");
        return 2;
    }
    if (!calibrationFile.empty() && growthDims.size() < 3) {
        std::fprintf(stderr, "auto_caster_bench: --write-calibration: the growth's fit needs 3 --growth-sizes or "
                     "more, not %zu\n", growthDims.size());
        return 2;
    }
    if (shortMode) {
        datasets = {"vtk_headmr"};
        size = 64, viewCount = 2, repeats = 1, to = {0.01}, ta = {3};
    }
    if (to.size() != ta.size()) {
        std::fprintf(stderr, "auto_caster_bench: --to and --ta need as many values\n");
        return 2;
    }
    const std::vector<Scene> measured = growthOnly ? std::vector<Scene>{} : scenes(datasets, phantomSize);
    const std::size_t rowCount = measured.size() * to.size();
    if (!calibrationFile.empty() && rowCount < std::size_t(kRowsToFit)) {
        std::fprintf(stderr, "auto_caster_bench: --write-calibration: the fit needs %d rows (datasets x settings) "
                     "or more, these options give %zu\n", kRowsToFit, rowCount);
        return 2;
    }

    bench::Checks checks("auto_caster_bench");
    try {
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx);
        const std::vector<ViewParams> views = benchViews(size, viewCount);
        std::printf("Device: %s. %dx%d, %zu views (ortho az 30 el 20, persp az 120 el 15, ortho az 200 el -25, "
                    "ortho az 0 el 0: the first %zu), %d repeat(s), step %g voxel, Phong headlight. Per caster: "
                    "device ms of the renders (sum over views of the median over repeats) + wall ms of uploading "
                    "its field once for the views (its bytes x the row's median ns per byte), and mean iterations "
                    "per pixel. Auto chooses once for the views, as volrender does for an orbit; its ms are those "
                    "of its choice.\n\n",
                    ctx.info().name.c_str(), size, size, views.size(), views.size(), repeats, step);
        std::printf("| dataset | voxels | T_o, T_a | regions | primitive | PC | ACD | EACD | fastest | auto | "
                    "auto / fastest | renders only | spread |\n"
                    "|---|---:|---|---:|---:|---:|---:|---:|---|---|---:|---:|---:|\n");
        double worst = 0;
        int within = 0, rows = 0;
        std::vector<double> spreads;
        std::vector<RenderSample> renderSamples;             // every caster's renders, per row
        std::vector<double> perByte;                         // wall ns per field byte uploaded, per row
        std::vector<double> blocksRatios;                    // a blocks MIP iteration over a primitive one, per scene
        for (const Scene& scene : measured) {
            StagedPreparation staged(scene.load());
            PrepareOptions options;
            options.classify.transferFunction = loadTransferFunction(scene.tf);
            for (std::size_t k = 0; k < to.size(); ++k) {
                StageTime statistics;
                const PreparedVolume& p = prepareSetting(staged, options, to[k], ta[k], statistics);
                if (k == 0) blocksRatios.push_back(blocksIterationRatio(renderer, p, views, repeats, step));
                const Timings t = measure(renderer, p, views, repeats, step);
                std::map<Caster, double> renders, totals;
                Caster fastest = Caster::Primitive, fastestRenders = Caster::Primitive;
                std::string cells;
                for (Caster c : kFixed) {
                    renders[c] = total(t.ms.at(c));
                    totals[c] = renders[c] + t.fieldUploadMs.at(c);
                    if (totals[c] < totals[fastest]) fastest = c;
                    if (renders[c] < renders[fastestRenders]) fastestRenders = c;
                    double iterations = 0;
                    for (double n : t.iterations.at(c)) iterations += n * size * size;
                    renderSamples.push_back({c, iterations / (views.size() * size * size),
                                             renders[c] * 1e6 / (views.size() * size * size)});
                    char cell[64];
                    std::snprintf(cell, sizeof cell, " %.1f + %.1f (%.1f) |", renders[c], t.fieldUploadMs.at(c),
                                  iterations / double(views.size() * size * size));
                    cells += cell;
                }
                perByte.push_back(t.uploadNsPerByte);
                const Caster chosen = t.chosen.caster;
                const double ratio = totals[chosen] / totals[fastest];
                spreads.push_back(spread(t.ms.at(fastest)));
                worst = std::max(worst, ratio);
                within += ratio <= kTarget;
                ++rows;
                std::printf("| %s | %zu | %g, %g | %u |%s %s %.1f | %s %.1f | %.2f%s | %.2f | %.0f %% |\n",
                            scene.name.c_str(), scene.voxels, to[k], ta[k], p.regions.count, cells.c_str(),
                            casterName(fastest).data(), totals[fastest], casterName(chosen).data(), totals[chosen],
                            ratio, ratio <= kTarget ? "" : " **over**", renders[chosen] / renders[fastestRenders],
                            100 * spreads.back());
                if (explain) {
                    std::printf("|  | statistics with the ray probe: %.0f ms wall, %.0f ms CPU; %s |||||||||||\n",
                                1e3 * statistics.seconds, 1e3 * statistics.cpuSeconds, t.chosen.reason.c_str());
                    for (std::size_t v = 0; v < views.size(); ++v) {
                        std::printf("|  | view %zu measured:", v);
                        for (Caster c : kFixed)
                            std::printf(" %s %.1f it, %.1f ms;", casterName(c).data(), t.iterations.at(c)[v],
                                        median(t.ms.at(c)[v]));
                        std::printf(" %s |||||||||||\n", t.viewEstimates[v].c_str());
                    }
                }
                std::fflush(stdout);
                checkRow(checks, scene.name + " at " + std::to_string(to[k]) + ", " + std::to_string(ta[k]), p,
                         scene.voxels, t, renders, ratio, spreads.back());
            }
        }
        if (growthOnly) {
            measureGrowth(checks, renderer, growthDims, views, repeats, step, builtInCalibration().rayNs);
            return checks.exitStatus();
        }
        if (!checks.expect(rows > 0, "no row: no dataset or phantom matched %zu prefix(es)", datasets.size()))
            return checks.exitStatus();
        std::printf("\nauto within %.0f %% of the fastest fixed caster on %d of %d rows; worst ratio %.2f.\n",
                    (kTarget - 1) * 100, within, rows, worst);
        std::printf("Run-to-run spread of the fastest fixed caster ((max - min) / median of its per-repeat sums over "
                    "the views): median %.0f %%, largest %.0f %%.\n",
                    100 * median(spreads), 100 * *std::max_element(spreads.begin(), spreads.end()));
        CasterCalibration fitted = builtInCalibration();  // the tie stays: it is the probe's precision
        fitted.uploadNsPerByte = median(perByte);
        if (rows >= kRowsToFit) {
            const std::array<double, 5> fit = fitModel(renderSamples);
            std::printf("Fit of the renders, device ns per pixel = ray + iterations x per-iteration "
                        "(a calibration's rayNs and iterationNs): ray %.0f;", fit[0]);
            for (Caster c : kFixed) std::printf(" %s %.0f;", casterName(c).data(), fit[1 + int(c)]);
            fitted.rayNs = fit[0];
            std::copy(fit.begin() + 1, fit.end(), fitted.iterationNs.begin());
        }
        fitted.blocksIterationRatio = median(blocksRatios);
        std::printf("\nA blocks MIP iteration over a primitive one (trilinear; a calibration's blocksIterationRatio): "
                    "median %.2f over %zu scene(s), from %.2f to %.2f.\n",
                    fitted.blocksIterationRatio, blocksRatios.size(),
                    *std::min_element(blocksRatios.begin(), blocksRatios.end()),
                    *std::max_element(blocksRatios.begin(), blocksRatios.end()));
        std::printf("Wall ns per field byte uploaded (median over rows): %.2f.\n", fitted.uploadNsPerByte);
        checks.expect(std::isfinite(fitted.uploadNsPerByte) && fitted.uploadNsPerByte >= 0,
                      "wall ns per field byte %g, not >= 0", fitted.uploadNsPerByte);
        if (!growthDims.empty())
            fitted.growth = measureGrowth(checks, renderer, growthDims, views, repeats, step, fitted.rayNs);
        if (!calibrationFile.empty()) {
            describeDevice(ctx, fitted);
            writeCasterCalibration(calibrationFile, fitted);
            std::printf("Calibration written to %s.\n", calibrationFile.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "auto_caster_bench: %s\n", e.what());
        return 1;
    }
    return checks.exitStatus();
}
