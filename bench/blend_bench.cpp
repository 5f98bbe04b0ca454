// Blend benchmark (prints a Markdown table): per shared CT, the median device time over an orbit of MIP with the
// primitive and the blocks caster (the figure to set beside VTK's MIP: `vr_peers --blend mip`, docs/BENCH.md), and
// of the iso-surface with both casters against the composite primitive caster, with iterations per ray; and the
// composite frame clipped to half the volume, by a crop box and by a plane, against the whole, in time and in samples
// taken (clipping should cost about its share of the frame: the share of the samples it keeps, half or less where
// the kept half holds half the work; more where it opens to view what the whole frame's rays ended before). The
// blocks caster must render its primitive caster's image (checked).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_checks.h"
#include "bench/counted_render.h"
#include "preprocess/classify/transfer_function.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "render/view_octants.h"
#include "support/datasets.h"
#include "support/load_dataset.h"
#include "sweep/order_statistics.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace {
using namespace vr;

// The scalar at which the TF's extinction first reaches half its largest: the surface the TF shows most.
double isoValueOf(const PreparedVolume& p) {
    const TransferTable& t = p.classification.table;
    const float largest = *std::max_element(t.sigma.begin(), t.sigma.end());
    std::size_t i = 0;
    while (i + 1 < t.size() && t.sigma[i] < largest / 2) ++i;
    return t.lo + double(i) * t.step;
}

struct Orbit {
    std::vector<double> ms;  // per view
    double medianMs = 0, iterationsPerRay = 0, samplesPerRay = 0;
    std::vector<Image> images;
};

// Each setting's orbit, the settings taking turns at each view, so that a machine whose speed drifts slows them
// alike and their per-view ratios (medianRatio) hold.
std::vector<Orbit> renderOrbits(VulkanRenderer& renderer, const GpuVolume& volume, const std::vector<Camera>& cameras,
                                const std::vector<RenderSettings>& settings) {
    for (const RenderSettings& s : settings) renderer.render(volume, cameras.front(), s);  // warm-up: compiled
    std::vector<Orbit> orbits(settings.size());
    std::vector<double> iterations(settings.size()), samples(settings.size()), rays(settings.size());
    for (const Camera& c : cameras) {
        for (std::size_t i = 0; i < settings.size(); ++i) {
            auto [r, deviceMs] = bench::timedThenCounted(renderer, volume, c, settings[i]);
            orbits[i].ms.push_back(deviceMs);
            for (uint32_t n : r.iterations) iterations[i] += n;
            for (uint32_t n : r.samples) samples[i] += n;
            rays[i] += double(r.iterations.size());
            orbits[i].images.push_back(std::move(r.image));
        }
    }
    for (std::size_t i = 0; i < settings.size(); ++i) {
        orbits[i].medianMs = median(orbits[i].ms);
        orbits[i].iterationsPerRay = iterations[i] / rays[i];
        orbits[i].samplesPerRay = samples[i] / rays[i];
    }
    return orbits;
}

Orbit renderOrbit(VulkanRenderer& renderer, const GpuVolume& volume, const std::vector<Camera>& cameras,
                  const RenderSettings& s) {
    return std::move(renderOrbits(renderer, volume, cameras, {s}).front());
}

// The median over the views of a's time over b's (rendered taking turns).
double medianRatio(const Orbit& a, const Orbit& b) {
    std::vector<double> r;
    for (std::size_t i = 0; i < a.ms.size(); ++i) r.push_back(a.ms[i] / b.ms[i]);
    return median(r);
}

double maxDifference(const Orbit& a, const Orbit& b) {
    double d = 0;
    for (std::size_t i = 0; i < a.images.size(); ++i) d = std::max(d, maxAbsDifference(a.images[i], b.images[i]));
    return d;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Blend benchmark: MIP and the iso-surface, primitive and blocks casters, against composite"};
    std::vector<std::string> datasets{"boston_teapot", "cranium_ct", "vtk_headsq_ct"};
    int size = 512, views = 4, device = -1;
    double step = 0.5;
    bool nearest = false;
    app.add_option("--datasets", datasets, "dataset name prefixes in MANIFEST.tsv")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", views, "views of the orbit (azimuth 360/N apart, elevation 0: vr_peers' views)")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    app.add_option("--step", step, "step in voxels of the smallest spacing")->capture_default_str();
    app.add_flag("--nearest", nearest, "nearest sampling (default: trilinear, as users render)");
    app.add_option("--device", device, "Vulkan device index");
    CLI11_PARSE(app, argc, argv);

    bench::Checks checks("blend_bench");
    try {
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx);
        std::printf("Device: %s. %dx%d, %d-view orbit (elevation 0), step %g voxel, %s; MIP and average unshaded, "
                    "iso and composite Phong with a headlight; composite with ERT 0.99.\n\n",
                    ctx.info().name.c_str(), size, size, views, step, nearest ? "nearest" : "trilinear");
        std::printf("| dataset | iso-value | MIP primitive ms | MIP blocks ms | MIP speed-up | MIP iterations "
                    "(prim / blocks) | composite primitive ms | iso primitive ms | iso blocks ms | composite / iso "
                    "blocks | iso iterations (prim / blocks) | half crop / whole: time (samples) | half plane / whole: "
                    "time (samples) |\n"
                    "|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---|---:|---:|\n");
        for (const std::string& name : datasets) {
            const test::DatasetEntry e = test::rawDataset(name);
            PrepareOptions options;
            options.classify.transferFunction = test::datasetTransferFunction(e.tf);
            options.fields = 0;  // neither caster reads a field
            const PreparedVolume p = prepare(test::loadDataset(e), options);
            std::vector<Camera> cameras;
            for (int i = 0; i < views; ++i) {
                ViewParams v;
                v.width = v.height = size;
                v.azimuthDeg = 360.0 * i / views;
                cameras.push_back(Camera::fit(p.grid(), v));
            }
            const GpuVolume volume = renderer.upload(p, {{Caster::Primitive, Caster::Blocks}, kAllOctants});
            RenderSettings s;
            s.stepVoxels = step;
            s.trilinear = !nearest;
            s.isoValue = isoValueOf(p);
            // Half the volume kept: the voxels of x below the middle, then the world half-space beyond the centre.
            RenderSettings cropSettings = s, planeSettings = s;
            const Vec3i dims = p.grid().dims;
            cropSettings.crop = CropBox{{0, 0, 0}, {dims.x / 2 - 1, dims.y - 1, dims.z - 1}};
            planeSettings.clipPlanes = {ClipPlane{{1, 0, 0}, p.grid().centre().x}};
            const std::vector<Orbit> clipped =
                renderOrbits(renderer, volume, cameras, {s, cropSettings, planeSettings});
            const Orbit &composite = clipped[0], &cropped = clipped[1], &planeClipped = clipped[2];
            s.shading = false;
            s.blend = Blend::MIP;
            const Orbit mip = renderOrbit(renderer, volume, cameras, s);
            s.caster = Caster::Blocks;
            const Orbit mipBlocks = renderOrbit(renderer, volume, cameras, s);
            s.shading = true;
            s.blend = Blend::Iso;
            const Orbit isoBlocks = renderOrbit(renderer, volume, cameras, s);
            s.caster = Caster::Primitive;
            const Orbit iso = renderOrbit(renderer, volume, cameras, s);
            checks.expect(maxDifference(mip, mipBlocks) <= 1e-5, "%s: MIP blocks renders MIP primitive's images",
                          name.c_str());
            checks.expect(maxDifference(iso, isoBlocks) <= 1e-5, "%s: iso blocks renders iso primitive's images",
                          name.c_str());
            checks.expect(mipBlocks.iterationsPerRay < mip.iterationsPerRay, "%s: MIP blocks iterates less",
                          name.c_str());
            std::printf("| %s | %g | %.3g | %.3g | %.2fx | %.1f / %.1f | %.3g | %.3g | %.3g | %.2fx | %.1f / %.1f | "
                        "%.2f (%.2f) | %.2f (%.2f) |\n",
                        name.c_str(), s.isoValue, mip.medianMs, mipBlocks.medianMs, mip.medianMs / mipBlocks.medianMs,
                        mip.iterationsPerRay, mipBlocks.iterationsPerRay, composite.medianMs, iso.medianMs,
                        isoBlocks.medianMs, composite.medianMs / isoBlocks.medianMs, iso.iterationsPerRay,
                        isoBlocks.iterationsPerRay, medianRatio(cropped, composite),
                        cropped.samplesPerRay / composite.samplesPerRay, medianRatio(planeClipped, composite),
                        planeClipped.samplesPerRay / composite.samplesPerRay);
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "blend_bench: %s\n", e.what());
        return 1;
    }
    return checks.exitStatus();
}
