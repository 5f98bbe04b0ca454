// Stereo benchmark (prints a Markdown table): per shared dataset, an orbit of stereo pairs whose right eye is the
// left eye's reprojection, cast again only where the reprojection cannot vouch for a pixel, against both eyes cast in
// full: the pair's median device time as a multiple of one eye's (and the reuse's left eye's, which records its
// bands), the share of the right eye cast again, and the reused right eye's error against its full render (PSNR,
// SSIM, % of pixels off by more than 1/255, % with CIEDE2000 > 2.3). The targets (docs/BENCH.md): the pair within
// 1.4 x one eye on the CTs; PSNR >= 40 dB and < 3 % of pixels with CIEDE2000 > 2.3 on every dataset. Each row says
// which it meets.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_checks.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "render/view_octants.h"
#include "support/load_dataset.h"
#include "sweep/stereo_measure.h"

namespace {
using namespace vr;

constexpr double kPairTarget = 1.4, kPsnrTarget = 40, kPerceptualTarget = 3;

bool isCt(const std::string& file) { return file.find("_ct_") != std::string::npos; }

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Stereo benchmark: the right eye reprojected from the left against both eyes cast in full"};
    std::vector<std::string> datasets;
    int size = 512, views = 8, rounds = 1, device = -1, pieces = VulkanRenderer::kAutoPieces;
    double to = 0.02, ta = 10, step = 0.5;
    std::string caster = "eacd", images;
    app.add_option("--datasets", datasets, "dataset name prefixes in MANIFEST.tsv (default: every raw dataset)")
        ->delimiter(',');
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", views, "pairs of the orbit (azimuth 360/N apart, elevation 20)")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    app.add_option("--rounds", rounds, "times the orbit is timed over, taking turns pair by pair (medians over all)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--caster", caster, "primitive, pc, acd, eacd or hier")->capture_default_str();
    app.add_option("--to", to, "T_o of the regions")->capture_default_str();
    app.add_option("--ta", ta, "T_a of the regions, degrees")->capture_default_str();
    app.add_option("--step", step, "step in voxels of the smallest spacing")->capture_default_str();
    app.add_option("--device", device, "Vulkan device index");
    app.add_option("--recast-pieces", pieces,
                   "pieces each composite re-cast ray is cast in (0: the device's choice: up to 8 pieces on a "
                   "discrete GPU, whole rays elsewhere)")
        ->check(CLI::Range(0, device::kMostPieces))
        ->capture_default_str();
    app.add_option("--images", images, "folder to write view 0's right eyes into: DATASET_reused.png, "
                                        "DATASET_full.png and DATASET_error.png (|difference| x 10)");
    CLI11_PARSE(app, argc, argv);

    bench::Checks checks("stereo_bench");
    try {
        if (datasets.empty())
            for (const test::DatasetEntry& e : test::rawManifest()) datasets.push_back(e.file);
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx);
        renderer.setRecastPieces(pieces);
        std::printf("Device: %s. %dx%d, %d-pair orbit (elevation 20), perspective (fov 30), separation 1/30 of the "
                    "focus distance (the volume centre's), %s caster at T_o %g, T_a %g, step %g voxel, trilinear, "
                    "Phong headlight, ERT 0.99. Times are medians over the orbit (%d round(s)); errors of the reused "
                    "right eye against its full render, mean over the views (worst view in brackets).\n\n",
                    ctx.info().name.c_str(), size, size, views, caster.c_str(), to, ta, step, rounds);
        std::printf("| dataset | one eye ms | pair ms (reuse) | pair / one eye | left eye ms (reuse) | "
                    "pair ms (no reuse) | reprojection ms | right eye re-cast (pixels, of them in part, work, "
                    "pieces) | PSNR dB | SSIM | off > 1/255 | CIEDE2000 > 2.3 | time target | quality target |\n"
                    "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n");
        for (const std::string& name : datasets) {
            const test::DatasetEntry e = test::rawDataset(name);
            PrepareOptions options;
            options.classify.transferFunction = test::datasetTransferFunction(e.tf);
            options.segmentation = {to, ta, true, true};
            RenderSettings s;
            s.caster = parseCaster(caster);
            if (s.caster == Caster::Hier) options.fields |= kFieldHier;  // built from the scalars, not the regions
            s.stepVoxels = step;
            s.trilinear = true;
            const PreparedVolume p = prepare(test::loadDataset(e), options);
            std::vector<Camera> cameras;
            for (int i = 0; i < views; ++i) {
                ViewParams v;
                v.projection = Projection::Perspective;
                v.width = v.height = size;
                v.azimuthDeg = 360.0 * i / views;
                v.elevationDeg = 20;
                cameras.push_back(Camera::fit(p.grid(), v));
            }
            const GpuVolume volume = renderer.upload(p, {{s.caster}, kAllOctants});
            const StereoMeasurement m = measureStereo(renderer, volume, cameras, s, rounds);
            if (!images.empty()) {
                const std::string stem = images + "/" + e.file.substr(0, e.file.find('.'));
                writeImage(stem + "_reused.png", m.reusedRight.front());
                writeImage(stem + "_full.png", m.fullRight.front());
                writeImage(stem + "_error.png", errorMap(m.fullRight.front(), m.reusedRight.front()));
            }
            const double ratio = m.pairMs / m.oneEyeMs;
            const bool quality = m.error.mean.psnr >= kPsnrTarget && m.error.mean.percentPerceptual < kPerceptualTarget;
            checks.expect(m.leftEyesEqual, "%s: the reuse's left eye is the full render's", e.file.c_str());
            checks.expect(m.recastFraction > 0 && m.recastFraction <= 1, "%s: a share of the right eye is re-cast",
                          e.file.c_str());
            checks.expect(m.recastInPart <= m.recastFraction, "%s: the pixels re-cast in part are re-cast",
                          e.file.c_str());
            checks.expect(m.pairMs > 0 && m.oneEyeMs > 0, "%s: positive device times", e.file.c_str());
            std::printf("| %s | %.3g | %.3g | %.2fx | %.3g | %.3g | %.3g | %.1f %%, %.1f %%, %.1f %%, %d | "
                        "%.1f (%.1f) | %.4f (%.4f) | %.2f %% (%.2f) | %.2f %% (%.2f) | %s | %s |\n",
                        e.file.c_str(), m.oneEyeMs, m.pairMs, ratio, m.leftEyeMs, m.fullPairMs, m.reprojectMs,
                        100 * m.recastFraction, 100 * m.recastInPart, 100 * m.recastWork, m.recastPieces,
                        m.error.mean.psnr, m.error.worst.psnr, m.error.mean.ssim, m.error.worst.ssim,
                        m.error.mean.percentOff8Bit,
                        m.error.worst.percentOff8Bit, m.error.mean.percentPerceptual, m.error.worst.percentPerceptual,
                        !isCt(e.file) ? "(not a CT)" : ratio <= kPairTarget ? "met" : "missed",
                        quality ? "met" : "missed");
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stereo_bench: %s\n", e.what());
        return 1;
    }
    return checks.exitStatus();
}
