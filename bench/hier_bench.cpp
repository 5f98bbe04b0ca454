// The hierarchical EACD against the flat one (docs/ALGORITHMS.md section 10; prints a Markdown table): per volume
// and field, the build's wall seconds and ns per voxel (the flat EACD: segmentation, ACD and EACD in the octants of
// the orbit, as volrender builds them; hier: the block ranges, the block regions and the EACD over them), the
// field's bytes as built and as uploaded, and on the Vulkan device the mean iterations per ray and the median
// device ms per frame of an orbit (trilinear, shaded), with the primitive caster for scale.
// Usage: hier_bench [--datasets NAME ...] [--clinical XxYxZ] [--size N] [--views N] [--to T] [--ta DEG]
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <numeric>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"
#include "preprocess/pipeline/hier_field.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "render/view_octants.h"
#include "resampled_volume.h"
#include "support/datasets.h"
#include "support/load_dataset.h"
#include "sweep/order_statistics.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace vr;

struct Source {
    std::string name;
    Volume volume;
    std::string tf;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Frames {
    double iterations = 0, medianMs = 0;
};

// Every view once after a warm-up frame: mean iterations per ray and median device ms.
Frames renderOrbit(VulkanRenderer& renderer, const PreparedVolume& p, Caster caster,
                   const std::vector<Camera>& cameras, unsigned octants, const RenderSettings& base) {
    RenderSettings s = base;
    s.caster = caster;
    const GpuVolume volume = renderer.upload(p, {{caster}, octants});
    Frames f;
    std::vector<double> ms;
    for (int v = -1; v < int(cameras.size()); ++v) {
        const RenderResult r = renderer.render(volume, cameras[std::size_t(std::max(v, 0))], s);
        if (v < 0) continue;
        ms.push_back(r.deviceMilliseconds);
        f.iterations += std::accumulate(r.iterations.begin(), r.iterations.end(), 0.0) / double(r.iterations.size()) /
                        double(cameras.size());
    }
    f.medianMs = median(ms);
    return f;
}

void row(const std::string& volume, const char* field, double seconds, std::size_t voxels, std::size_t bytes,
         std::size_t uploaded, const Frames& f) {
    std::printf("| %s | %s | %.3f | %.1f | %.2f | %.2f | %.1f | %.1f |\n", volume.c_str(), field, seconds,
                seconds * 1e9 / double(voxels), double(bytes) / 1e6, double(uploaded) / 1e6, f.iterations, f.medianMs);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The hierarchical EACD against the flat EACD: build time, bytes, iterations per ray, device ms"};
    std::vector<std::string> datasets{"boston_teapot", "cranium_ct", "vtk_headsq_ct"};
    std::string clinical;
    int size = 512, views = 4, device = -1;
    double to = 0.01, ta = 3;
    app.add_option("--datasets", datasets, "dataset name prefixes in MANIFEST.tsv")->capture_default_str();
    app.add_option("--clinical", clinical, "also a CT of XxYxZ voxels resampled from the cranium CT with noise of 20 "
                                           "(as bench/make_clinical_volume makes it), e.g. 512x512x1024");
    app.add_option("--size", size, "image width = height")->capture_default_str();
    app.add_option("--views", views, "views of the orbit (azimuth 360/N apart, elevation 20)")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str();
    app.add_option("--to", to, "T_o (volrender's default)")->capture_default_str();
    app.add_option("--ta", ta, "T_a, degrees (volrender's default)")->capture_default_str();
    app.add_option("--device", device, "Vulkan device index");
    CLI11_PARSE(app, argc, argv);

    try {
        std::vector<Source> sources;
        for (const std::string& name : datasets) {
            const test::DatasetEntry e = test::rawDataset(name);
            sources.push_back({e.file, test::loadDataset(e), e.tf});
        }
        if (!clinical.empty()) {
            Vec3i dims;
            if (std::sscanf(clinical.c_str(), "%dx%dx%d", &dims.x, &dims.y, &dims.z) != 3)
                throw InputError("--clinical: expected XxYxZ, got " + clinical);
            const test::DatasetEntry e = test::rawDataset("cranium_ct");
            Volume ct = bench::withNoise(bench::resample(test::loadDataset(e), dims), 20, 1);
            sources.push_back({"clinical_ct_" + clinical, std::move(ct), e.tf});
        }
        VulkanContext ctx(VulkanOptions{device, false});
        VulkanRenderer renderer(ctx);
        std::printf("Device: %s. %dx%d, %d-view orbit (elevation 20), step 0.5 voxel, trilinear, Phong headlight, "
                    "T_o %g, T_a %g.\n\n", ctx.info().name.c_str(), size, size, views, to, ta);
        std::printf("| volume | field | build s | build ns/voxel | MB built | MB uploaded | iterations/ray | "
                    "median device ms |\n|---|---|---|---|---|---|---|---|\n");
        for (Source& src : sources) {
            const std::size_t voxels = src.volume.grid.voxels();
            RenderSettings s;
            s.trilinear = true;
            ViewParams orbit;
            orbit.width = orbit.height = size;
            orbit.elevationDeg = 20;
            const std::vector<Camera> cameras = Camera::orbit(src.volume.grid, orbit, views);
            unsigned octants = 0;
            for (const Camera& camera : cameras) octants |= viewOctants(camera);
            PrepareOptions options;
            options.classify.transferFunction = test::datasetTransferFunction(src.tf);
            options.segmentation = {to, ta, true, true};
            options.octants = octants;
            options.keepRegions = false;
            options.fields = 0;
            StagedPreparation staged(std::move(src.volume));
            staged.prepare(options);
            row(src.name, "none (primitive)", 0, voxels, 0, 0,
                renderOrbit(renderer, staged.prepare(options), Caster::Primitive, cameras, octants, s));

            options.fields = kFieldEACD;
            const PreparedVolume& flat = staged.prepare(options);
            double flatSeconds = 0;
            for (const StageTime& t : staged.lastStages()) flatSeconds += t.seconds;
            const std::size_t flatBytes = fieldBytesOf(flat.fields).eacd;
            row(src.name, "flat EACD (log16)", flatSeconds, voxels, flatBytes, flatBytes,
                renderOrbit(renderer, flat, Caster::EACD, cameras, octants, s));

            options.fields = 0;
            PreparedVolume p = staged.prepare(options);  // the scalars and their classification
            for (int shift : {2, 3}) {
                const auto start = std::chrono::steady_clock::now();
                p.fields.hier = buildHierarchicalEACD(p, options.segmentation, octants, shift);
                p.meta.segmentation = options.segmentation;
                const double seconds = secondsSince(start);
                const std::string name = "hier, blocks of " + std::to_string(1 << shift);
                row(src.name, name.c_str(), seconds, voxels, p.fields.hier.bytes(), p.fields.hier.bytes(),
                    renderOrbit(renderer, p, Caster::Hier, cameras, octants, s));
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hier_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
