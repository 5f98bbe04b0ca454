// EACD extent codes (core/extent_code.h) compared (prints Markdown tables): per dataset and threshold setting, the
// EACD caster on the device with exact extents (3 bytes per octant), log16 (2) and joint8 (1): bytes per voxel
// stored and uploaded, mean iterations per ray and median device time over an orbit after one warm-up frame, both
// as ratios to exact and to log16, the wall and process CPU time of the orbit, and the worst view's PSNR against
// the exact code's image. Iterations do not depend on the device; times do (measure them on a quiet GPU).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "bench_checks.h"
#include "core/extent_code.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "support/datasets.h"
#include "support/load_dataset.h"
#include "sweep/metrics/rmse.h"
#include "sweep/order_statistics.h"
#include "render/cpu_renderer.h"
#include "render/view_octants.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace vr;

constexpr ExtentCode kCodes[] = {ExtentCode::Exact, ExtentCode::Log16, ExtentCode::Joint8};



struct CodeRun {
    double iterations = 0, deviceMs = 0, deviceBytesPerVoxel = 0;
    StageTime orbit;
    double worstPsnr = INFINITY;
};

constexpr uint32_t kIterationMask = 0x3fffffffu;  // the renderer's flags sit above the count

// Iterations do not depend on the device: the device's loop counts of one view, pixel by pixel, are the CPU
// reference's on the same coded volume (rendered again, after the orbit was timed).
void checkIterationsMatchCpu(bench::Checks& checks, const std::string& row, VulkanRenderer& renderer,
                             const GpuVolume& volume, const PreparedVolume& p, const Camera& camera,
                             const RenderSettings& s) {
    const RenderResult device = renderer.render(volume, camera, s);
    const RenderResult cpu = renderCpu(p, camera, s);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < cpu.iterations.size(); ++i)
        differ += (device.iterations[i] & kIterationMask) != (cpu.iterations[i] & kIterationMask);
    checks.expect(device.iterations.size() == cpu.iterations.size() && differ == 0,
                  "%s: %zu of %zu pixels of the first view took other iterations on the device than on the CPU",
                  row.c_str(), differ, cpu.iterations.size());
}

// What the rows of one setting say: every code looped, took device and wall time, and uploaded the bytes of its
// texels for each octant of the orbit (exact's 3 bytes travel in a 4-byte RGBA8 texel); the exact code's image is
// its own reference. At thresholds 0 a box rounded down is still homogeneous, so every code renders the exact
// code's image (the primitive image, up to float rounding) and needs no fewer fetches than a finer code (within
// the 2 % by which paths differ once leaps do).
void checkSetting(bench::Checks& checks, const std::string& setting, const std::array<CodeRun, 3>& runs,
                  unsigned octants, bool zeroThresholds) {
    for (ExtentCode code : kCodes) {
        const CodeRun& r = runs[int(code)];
        const std::string row = setting + " " + std::string(extentCodeName(code));
        checks.expect(r.iterations > 0, "%s: %g iterations per ray, not > 0", row.c_str(), r.iterations);
        checks.expect(r.deviceMs > 0, "%s: median device ms %g, not > 0", row.c_str(), r.deviceMs);
        checks.expect(r.orbit.seconds > 0 && r.orbit.cpuSeconds >= 0, "%s: orbit took %g wall s, %g CPU s",
                      row.c_str(), r.orbit.seconds, r.orbit.cpuSeconds);
        const double texelBytes = code == ExtentCode::Exact ? 4.0 : double(extentCodeBytes(code));
        checks.expect(r.deviceBytesPerVoxel == texelBytes * std::popcount(octants),
                      "%s: %g device bytes per voxel, not %g bytes for each of %d octants", row.c_str(),
                      r.deviceBytesPerVoxel, texelBytes, std::popcount(octants));
        if (code == ExtentCode::Exact) {
            checks.expect(r.worstPsnr == INFINITY, "%s: PSNR %g dB against its own images", row.c_str(), r.worstPsnr);
        } else if (zeroThresholds) {
            checks.expect(r.worstPsnr >= 90, "%s: PSNR %g dB against exact at thresholds 0, not >= 90 (equal images)",
                          row.c_str(), r.worstPsnr);
            const CodeRun& finer = runs[int(code) - 1];
            checks.expect(r.iterations >= finer.iterations / 1.02,
                          "%s: %g iterations per ray at thresholds 0, fewer than the finer code's %g", row.c_str(),
                          r.iterations, finer.iterations);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"EACD extent codes on the device: exact vs log16 vs joint8, iterations per ray and device time"};
    std::vector<std::string> datasets{"boston_teapot", "cranium_ct"};
    int size = 512, views = 4, device = -1;
    double to = 0.02, ta = 10, step = 0.5;
    app.add_option("--datasets", datasets, "dataset name prefixes in MANIFEST.tsv")->capture_default_str();
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", views, "views of the orbit (azimuth 360/N apart, elevation 20)")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    app.add_option("--to", to, "T_o of the second threshold setting (the first is 0)")->capture_default_str();
    app.add_option("--ta", ta, "T_a of the second threshold setting, degrees")->capture_default_str();
    app.add_option("--step", step, "step in voxels")->capture_default_str();
    app.add_option("--device", device, "Vulkan device index");
    bool quick = false;
    app.add_flag("--short", quick, "a quick run for CI: 64x64, 2 views, the teapot only");
    CLI11_PARSE(app, argc, argv);
    if (quick) size = 64, views = 2, datasets = {"boston_teapot"};

    bench::Checks checks("extent_code_bench");
    int rowsPrinted = 0;
    try {
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx);
        std::printf("Device: %s. %dx%d, %d-view orbit (elevation 20), step %g voxel, nearest, Phong headlight, "
                    "ERT 0.99, EACD caster.\n\n",
                    ctx.info().name.c_str(), size, size, views, step);
        std::printf("Stored bytes per voxel (8 octants): PC 1, ACD 8, EACD exact %zu, log16 %zu, joint8 %zu.\n\n",
                    kOctants * extentCodeBytes(ExtentCode::Exact), kOctants * extentCodeBytes(ExtentCode::Log16),
                    kOctants * extentCodeBytes(ExtentCode::Joint8));
        std::printf("| dataset | T_o, T_a | code | device B/voxel (octants of the orbit) | iterations/ray | "
                    "x exact | x log16 | median device ms | x exact | x log16 | orbit wall s (CPU s) | "
                    "PSNR vs exact, worst view (dB) |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (const std::string& name : datasets) {
            const test::DatasetEntry dataset = test::rawDataset(name);
            PrepareOptions options;
            options.classify.transferFunction = test::datasetTransferFunction(dataset.tf);
            options.fields = kFieldEACD;
            options.eacdCode = ExtentCode::Exact;
            StagedPreparation staged(test::loadDataset(dataset));
            std::vector<Camera> cameras;
            unsigned octants = 0;
            for (int v = 0; v < views; ++v) {
                ViewParams vp;
                vp.width = vp.height = size;
                vp.azimuthDeg = 360.0 * v / views;
                vp.elevationDeg = 20;
                cameras.push_back(Camera::fit(staged.volume().grid, vp));
                octants |= viewOctants(cameras.back());
            }
            for (auto [settingTo, settingTa] : {std::pair{0.0, 0.0}, std::pair{to, ta}}) {
                options.segmentation = {settingTo, settingTa, true, false};
                const PreparedVolume& exact = staged.prepare(options);
                RenderSettings s;
                s.caster = Caster::EACD;
                s.stepVoxels = step;
                std::vector<Image> reference;  // the exact code's image per view
                std::array<CodeRun, 3> runs;
                for (ExtentCode code : kCodes) {
                    PreparedVolume p = exact;
                    quantiseEACD(p.fields, code);
                    const GpuVolume volume = renderer.upload(p, {{Caster::EACD}, octants});
                    CodeRun& run = runs[int(code)];
                    for (const UploadedResource& u : volume.uploads())
                        if (u.name == "eacd") run.deviceBytesPerVoxel += double(u.bytes) / double(p.grid().voxels());
                    renderer.render(volume, cameras[0], s);  // warm-up
                    std::vector<double> ms;
                    const StageClock clock;
                    for (int v = 0; v < views; ++v) {
                        const RenderResult r = renderer.render(volume, cameras[v], s);
                        ms.push_back(r.deviceMilliseconds > 0 ? r.deviceMilliseconds : r.wallMilliseconds);
                        run.iterations += std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0) /
                                          double(r.iterations.size()) / views;
                        if (code == ExtentCode::Exact) reference.push_back(r.image);
                        run.worstPsnr = std::min(run.worstPsnr, difference(reference[v], r.image).psnr());
                    }
                    run.orbit = clock.stop("orbit");
                    run.deviceMs = median(ms);
                    checkIterationsMatchCpu(checks,
                                            dataset.file + " " + std::to_string(settingTo) + ", " +
                                                std::to_string(settingTa) + " " + std::string(extentCodeName(code)),
                                            renderer, volume, p, cameras[0], s);
                }
                for (ExtentCode code : kCodes) {
                    const CodeRun& r = runs[int(code)];
                    const CodeRun &e = runs[int(ExtentCode::Exact)], &l = runs[int(ExtentCode::Log16)];
                    std::printf("| %s | %g, %g | %s | %.0f | %.2f | %.3f | %.3f | %.1f | %.3f | %.3f | %.2f (%.2f) "
                                "| %.1f |\n",
                                dataset.file.c_str(), settingTo, settingTa, std::string(extentCodeName(code)).c_str(),
                                r.deviceBytesPerVoxel, r.iterations, r.iterations / e.iterations,
                                r.iterations / l.iterations, r.deviceMs, r.deviceMs / e.deviceMs,
                                r.deviceMs / l.deviceMs, r.orbit.seconds, r.orbit.cpuSeconds, r.worstPsnr);
                    std::fflush(stdout);
                    ++rowsPrinted;
                }
                const std::string setting = std::to_string(settingTo) + ", " + std::to_string(settingTa);
                checkSetting(checks, dataset.file + " at " + setting, runs, octants, settingTo == 0 && settingTa == 0);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "extent_code_bench: %s\n", e.what());
        return 1;
    }
    checks.expect(rowsPrinted > 0, "no row printed: no dataset was given");
    return checks.exitStatus();
}
