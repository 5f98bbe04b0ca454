// --caster auto against the fixed casters (issue 6): on every raw dataset of the shared MANIFEST.tsv and the
// synthetic phantoms, the median device ms over a few views of each fixed caster and of auto's choice per view
// (volrender/caster_choice.h, from the statistics volprep stores), and auto's ratio to the fastest fixed caster
// (target: at most 1.10). Prints a Markdown table. --short: one tiny dataset at 64x64 (CTest, label bench).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>

#include "datasets/phantoms.h"
#include "preprocess/classify/classify.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/prepare.h"
#include "preprocess/segment/segment.h"
#include "support/datasets.h"
#include "sweep/order_statistics.h"
#include "volrender/caster_choice.h"
#include "volrender/vulkan/view_octants.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace vr;

constexpr double kTarget = 1.10;  // auto within 10 % of the fastest fixed caster
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
    all.resize(std::min<std::size_t>(all.size(), std::size_t(std::max(count, 1))));
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

// Classify, segment and build every field at one setting, with the statistics volprep would store.
PreparedVolume prepare(const Volume& volume, const fs::path& tf, double to, double ta) {
    PreparedVolume p;
    ClassifyParams cp;
    cp.transferFunction = loadTransferFunction(tf);
    p.classified = classify(volume, cp);
    p.meta.segmentation = {to, ta, true, false};
    p.regions = segment(p.classified, p.meta.segmentation);
    p.fields = buildFields(p.regions, kFieldPC | kFieldACD | kFieldEACD);
    p.meta.statistics = preparedStatistics(p, {});
    return p;
}

struct Timings {
    std::map<Caster, std::vector<double>> fixed;  // device ms per (view, repeat)
    std::vector<double> autoMs;
    std::map<Caster, int> chosen;                 // auto's choices over the views
    std::vector<std::string> reasons;             // auto's estimates per view
};

// Every view `repeats` times, the fixed casters taking turns within a view (in a rotating order) so that a busy
// machine slows them alike; one warm-up frame per caster first. Auto's render of a view IS the render of the
// caster it chose (the choice is a few operations on the statistics), so its time per view is that render's:
// rendering it again would only add the machine's noise to the comparison.
Timings measure(VulkanRenderer& renderer, const PreparedVolume& p, const std::vector<ViewParams>& views, int repeats,
                double step) {
    Timings t;
    RenderSettings s;
    s.stepVoxels = step;
    std::vector<Camera> cameras;
    GpuVolumeContents contents{{std::begin(kFixed), std::end(kFixed)}, s.shading, 0};
    for (const ViewParams& v : views) {
        cameras.push_back(Camera::fit(p.classified.grid, v));
        contents.octants |= viewOctants(cameras.back());
    }
    const GpuVolume volume = renderer.upload(p, contents);  // once for every caster and view
    for (Caster c : kFixed) {
        s.caster = c;
        renderer.render(volume, cameras.front(), s);
    }
    int turn = 0;
    for (int r = 0; r < repeats; ++r)
        for (std::size_t i = 0; i < views.size(); ++i) {
            const ViewParams& v = views[i];
            const Camera& camera = cameras[i];
            const CasterDemand demand{v.projection, camera.forward, viewOctants(camera),
                                      (long long)v.width * v.height, step, int(views.size())};
            const CasterChoice choice = chooseCaster(p.meta.statistics, demand);
            if (r == 0) {
                ++t.chosen[choice.caster];
                t.reasons.push_back(choice.reason);
            }
            for (int k = 0; k < 4; ++k) {
                s.caster = kFixed[(k + turn) % 4];
                t.fixed[s.caster].push_back(renderer.render(volume, camera, s).deviceMilliseconds);
                if (s.caster == choice.caster) t.autoMs.push_back(t.fixed[s.caster].back());
            }
            ++turn;
        }
    return t;
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
    app.add_flag("--short", shortMode, "one tiny dataset (vtk_headmr), 64x64, 2 views, once: a few seconds (CTest)");
    app.add_flag("--explain", explain, "print auto's estimates for every view below each row");
    app.add_option("--datasets", datasets, "dataset name prefixes (MANIFEST.tsv files, phantom_NAME); default all")
        ->delimiter(',');
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", viewCount, "views (1..4: ortho, persp, ortho, ortho)")->capture_default_str();
    app.add_option("--repeats", repeats, "renders of every view per caster")->capture_default_str();
    app.add_option("--phantom-size", phantomSize, "edge of the phantoms")->capture_default_str();
    app.add_option("--to", to, "T_o per setting")->delimiter(',')->capture_default_str();
    app.add_option("--ta", ta, "T_a per setting (as many as --to), degrees")->delimiter(',')->capture_default_str();
    app.add_option("--step", step, "step in voxels")->capture_default_str();
    app.add_option("--device", device, "Vulkan device index");
    CLI11_PARSE(app, argc, argv);
    if (shortMode) {
        datasets = {"vtk_headmr"};
        size = 64, viewCount = 2, repeats = 1, to = {0.01}, ta = {3};
    }
    if (to.size() != ta.size()) {
        std::fprintf(stderr, "auto_caster_bench: --to and --ta need as many values\n");
        return 2;
    }

    try {
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx);
        const std::vector<ViewParams> views = benchViews(size, viewCount);
        std::printf("Device: %s. %dx%d, %zu views (ortho az 30 el 20, persp az 120 el 15, ortho az 200 el -25, "
                    "ortho az 0 el 0: the first %zu), %d repeat(s), step %g voxel, Phong headlight. Median device "
                    "ms over views x repeats; auto picks per view from the prepared statistics, its time per view "
                    "is that of the caster it picked.\n\n",
                    ctx.info().name.c_str(), size, size, views.size(), views.size(), repeats, step);
        std::printf("| dataset | voxels | T_o, T_a | regions | primitive | PC | ACD | EACD | auto (choices) | "
                    "auto / fastest |\n|---|---:|---|---:|---:|---:|---:|---:|---|---:|\n");
        double worst = 0;
        int within = 0, rows = 0;
        for (const Scene& scene : scenes(datasets, phantomSize)) {
            const Volume volume = scene.load();
            for (std::size_t k = 0; k < to.size(); ++k) {
                const PreparedVolume p = prepare(volume, scene.tf, to[k], ta[k]);
                const Timings t = measure(renderer, p, views, repeats, step);
                double fastest = INFINITY;
                std::string cells;
                for (Caster c : kFixed) {
                    const double ms = median(t.fixed.at(c));
                    fastest = std::min(fastest, ms);
                    char cell[32];
                    std::snprintf(cell, sizeof cell, " %.1f |", ms);
                    cells += cell;
                }
                std::string choices;
                for (const auto& [c, n] : t.chosen)
                    choices += (choices.empty() ? "" : " ") + std::string(casterName(c)) + "x" + std::to_string(n);
                const double autoMs = median(t.autoMs), ratio = autoMs / fastest;
                worst = std::max(worst, ratio);
                within += ratio <= kTarget;
                ++rows;
                std::printf("| %s | %zu | %g, %g | %u |%s %.1f (%s) | %.2f%s |\n", scene.name.c_str(),
                            scene.voxels, to[k], ta[k], p.regions.count, cells.c_str(), autoMs,
                            choices.c_str(), ratio, ratio <= kTarget ? "" : " **over**");
                if (explain)
                    for (std::size_t v = 0; v < t.reasons.size(); ++v)
                        std::printf("|  | view %zu: %s |||||||||\n", v, t.reasons[v].c_str());
                std::fflush(stdout);
            }
        }
        std::printf("\nauto within %.0f %% of the fastest fixed caster on %d of %d rows; worst ratio %.2f.\n",
                    (kTarget - 1) * 100, within, rows, worst);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "auto_caster_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
