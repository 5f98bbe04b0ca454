// Render benchmark (prints a Markdown table): per dataset, threshold setting, caster and gradient source, the time
// of the one upload the orbit shares, the median device time over the orbit after one warm-up frame, the mean
// iterations per ray, both as ratios to the primitive caster, and the PSNR of the images against the primitive
// caster's at thresholds 0 (with the first gradient source).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "bench/counted_render.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "support/datasets.h"
#include "support/load_dataset.h"
#include "sweep/metrics/rmse.h"
#include "sweep/order_statistics.h"
#include "render/view_octants.h"
#include "volrender/vulkan/vulkan_renderer.h"

using namespace vr;

int main(int argc, char** argv) {
    CLI::App app{"Vulkan caster benchmark: device time and iterations per ray of primitive, PC, ACD and EACD"};
    std::vector<std::string> datasets{"boston_teapot", "cranium_ct"};
    int size = 512, views = 8, device = -1;
    double to = 0.02, ta = 10, step = 0.5;
    bool nearest = false, noShading = false;
    int tile = VulkanRenderer::kAutoTile, pieces = 1;
    std::vector<std::string> gradientSources{"on-the-fly"};
    app.add_option("--datasets", datasets, "dataset name prefixes in MANIFEST.tsv")->capture_default_str();
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", views, "views of the orbit (azimuth 360/N apart, elevation 20)")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    app.add_option("--to", to, "T_o of the threshold setting")->capture_default_str();
    app.add_option("--ta", ta, "T_a of the threshold setting, degrees")->capture_default_str();
    app.add_option("--step", step, "step in voxels")->capture_default_str();
    app.add_flag("--nearest", nearest, "nearest sampling and regions for it (default: trilinear, as users render)");
    app.add_flag("--no-shading", noShading, "emission-absorption only, regions without normals (default: Phong)");
    app.add_option("--device", device, "Vulkan device index");
    app.add_option("--tile", tile, "pixels per side of one submit (0: the renderer's choice for the device)")
        ->check(CLI::Range(0, 16384))
        ->capture_default_str();
    app.add_option("--ray-pieces", pieces,
                   "pieces each composite ray is cast in (1: whole rays, as users render; more: to measure where a "
                   "GPU's frame waits on its longest rays)")
        ->check(CLI::Range(1, device::kMostPieces))
        ->capture_default_str();
    app.add_option("--gradients", gradientSources, "what shading takes its normals from, each in turn: on-the-fly, "
                   "stored")->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx, tile);
        renderer.setRayPieces(pieces);
        std::printf("Device: %s. %dx%d, %d-view orbit (elevation 20), step %g voxel, %s, %s, ERT 0.99, tiles of %d "
                    "px, rays in %d piece(s).\n\n",
                    ctx.info().name.c_str(), size, size, views, step, nearest ? "nearest" : "trilinear",
                    noShading ? "unshaded" : "Phong headlight", renderer.tileSize(), pieces);
        std::printf("| dataset | T_o, T_a | caster | gradients | upload ms (MB) | median device ms | "
                    "x primitive (time) | iterations/ray | most iterations of a ray | x primitive (iterations) | "
                    "PSNR vs primitive T=0, worst view (dB) |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (const std::string& name : datasets) {
            const test::DatasetEntry e = test::rawDataset(name);
            PrepareOptions options;
            options.classify.transferFunction = test::datasetTransferFunction(e.tf);
            StagedPreparation staged(test::loadDataset(e));
            std::vector<Image> reference;  // primitive at thresholds 0, per view
            for (auto [settingTo, settingTa] : {std::pair{0.0, 0.0}, std::pair{to, ta}}) {
                options.segmentation = {settingTo, settingTa, !noShading, !nearest};
                options.classify.normals = !noShading;
                const PreparedVolume& p = staged.prepare(options);
                double primitiveMs = 0, primitiveIterations = 0;
                for (Caster c : {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD})
                for (const std::string& source : gradientSources) {
                    RenderSettings s;
                    s.caster = c;
                    s.stepVoxels = step;
                    s.trilinear = !nearest;
                    s.shading = !noShading;
                    s.gradients = parseGradients(source);
                    std::vector<double> ms, psnrs;
                    double iterations = 0;
                    uint32_t most = 0;  // a ray's iterations, with its pieces' summed: the longest chain of whole rays
                    std::vector<Camera> cameras;
                    unsigned octants = 0;
                    for (int v = 0; v < views; ++v) {
                        ViewParams vp;
                        vp.width = vp.height = size;
                        vp.azimuthDeg = 360.0 * v / views;
                        vp.elevationDeg = 20;
                        cameras.push_back(Camera::fit(p.grid(), vp));
                        octants |= viewOctants(cameras.back());
                    }
                    const auto start = std::chrono::steady_clock::now();
                    const GpuVolume volume =
                        renderer.upload(p, {{c}, octants, s.readsStoredGradients()});
                    const double uploadMs =
                        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                    for (int v = -1; v < views; ++v) {  // v = -1: the warm-up frame
                        const Camera& camera = cameras[std::max(v, 0)];
                        const auto [r, deviceMs] = bench::timedThenCounted(renderer, volume, camera, s);
                        if (v < 0) continue;
                        ms.push_back(deviceMs);
                        iterations += std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0) /
                                      double(r.iterations.size()) / views;
                        most = std::max(most, *std::max_element(r.iterations.begin(), r.iterations.end()));
                        if (reference.size() < std::size_t(views)) reference.push_back(r.image);
                        psnrs.push_back(difference(reference[v], r.image).psnr());
                    }
                    const double t = median(ms);
                    if (c == Caster::Primitive && source == gradientSources.front())
                        primitiveMs = t, primitiveIterations = iterations;
                    std::printf("| %s | %g, %g | %s | %s | %.1f (%.1f) | %.3g | %.2f | %.1f | %u | %.2f | %.1f |\n",
                                e.file.c_str(), settingTo, settingTa, std::string(casterName(c)).c_str(),
                                source.c_str(), uploadMs,
                                double(volume.uploadedBytes()) / 1e6, t, primitiveMs / t, iterations, most,
                                primitiveIterations / iterations, *std::min_element(psnrs.begin(), psnrs.end()));
                    std::fflush(stdout);
                }
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
