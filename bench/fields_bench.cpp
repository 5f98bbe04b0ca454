// Distance-field build times and mean leap lengths, on synthetic regions (constant, random-blocky) and on real
// datasets (loaded, classified with their manifest TF, segmented with the default parameters).
// Usage: fields_bench [--repeat N] [N | NXxNYxNZ | DATASET.raw.gz ...]   (default: 128 256, i.e. 128^3 and 256^3)
// Per volume: the shared path (buildFields' steps: axial runs, the 8 ACDs, PC from them, the 8 EACDs on the same
// runs) and the stand-alone builders (buildPC, buildACD per octant, buildEACD), wall and CPU seconds each: the
// fastest of N runs (default 1); and a checksum of each field.
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <optional>
#include <random>
#include <string>

#include "io/crc32.h"
#include "preprocess/classify/classify.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/load/load_volume.h"
#include "preprocess/segment/segment.h"
#include "support/datasets.h"

namespace {

using namespace vr;
using Clock = std::chrono::steady_clock;

// Wall and CPU seconds (all threads, TBB's brief spinning included) of one build: the machine may be shared,
// so both are printed.
struct Timer {
    Clock::time_point wall = Clock::now();
    std::clock_t cpu = std::clock();
    std::string done() const {
        char text[64];
        const double seconds = std::chrono::duration<double>(Clock::now() - wall).count();
        std::snprintf(text, sizeof text, "%6.3f s (cpu %6.3f s)", seconds, double(std::clock() - cpu) / CLOCKS_PER_SEC);
        return text;
    }
};

Regions constantVolume(Vec3i dims) {
    Regions r;
    r.dims = dims;
    r.label.assign(voxelCount(r.dims), 0);
    r.count = 1;
    return r;
}

// 4 n random axis-aligned boxes of edge 1..n/4 (n the largest dimension) painted with 8 labels: regions of
// every size and shape.
Regions blockyVolume(Vec3i dims) {
    Regions r = constantVolume(dims);
    r.count = 8;
    const int n = maxComponent(dims);
    std::mt19937 rng(42);
    std::uniform_int_distribution<int> edge(1, std::max(1, n / 4)), label(0, 7);
    for (int b = 0; b < 4 * n; ++b) {
        Vec3i lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::uniform_int_distribution<int>(0, dims[a] - 1)(rng);
            hi[a] = std::min(dims[a], lo[a] + edge(rng));
        }
        const uint32_t l = label(rng);
        for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y)
                for (int x = lo.x; x < hi.x; ++x) r.label[linearIndex(r.dims, x, y, z)] = l;
    }
    return r;
}

Regions datasetRegions(const std::string& file) {
    ClassifyParams classify;
    classify.transferFunction = loadTransferFunction(test::datasetsDir() / test::dataset(file).tf);
    return segment(vr::classify(loadVolume(test::datasetsDir() / file), classify), SegmentationParams{});
}

// Times f() `repeat` times and keeps the fastest (wall and CPU), for a machine shared with others.
template <typename F>
std::string fastest(int repeat, F f) {
    std::string best;
    double bestWall = 1e300;
    for (int i = 0; i < repeat; ++i) {
        Timer t;
        f();
        const double wall = std::chrono::duration<double>(Clock::now() - t.wall).count();
        if (wall < bestWall) bestWall = wall, best = t.done();
    }
    return best;
}

void run(const std::string& name, const Regions& r, int repeat) {
    std::printf("%-14s %dx%dx%d, %u regions\n", name.c_str(), r.dims.x, r.dims.y, r.dims.z, r.count);

    // buildFields' path: the runs, ACDs and PC shared.
    ACDFields acd;
    std::vector<uint8_t> pc;
    std::array<ExtentField, kOctants> eacd;
    std::optional<AxialRuns> runs;
    const std::string runsTime = fastest(repeat, [&] {
        runs.emplace(r);
        runs->computeAll();
    });
    const std::string acdTime = fastest(repeat, [&] { acd = buildACDs(*runs); });
    const std::string pcTime = fastest(repeat, [&] { pc = pcFromACD(acd); });
    const std::string eacdTime = fastest(repeat, [&] { eacd = buildEACD(*runs, acd); });
    std::printf("  shared:      runs x6 %s   ACD x8 %s   PC %s   EACD x8 %s\n", runsTime.c_str(), acdTime.c_str(),
                pcTime.c_str(), eacdTime.c_str());

    // Each builder on its own, as the pipeline's stages call them (each computes the runs it needs).
    std::vector<uint8_t> alonePC;
    const std::string alonePCTime = fastest(repeat, [&] { alonePC = buildPC(r); });
    const std::string aloneACDTime = fastest(repeat, [&] {
        for (int o = 0; o < kOctants; ++o) buildACD(r, o);
    });
    const std::string aloneEACDTime = fastest(repeat, [&] { buildEACD(r, acd); });
    std::printf("  stand-alone: PC %s   ACD x8 %s   EACD x8 %s\n", alonePCTime.c_str(), aloneACDTime.c_str(),
                aloneEACDTime.c_str());
    if (alonePC != pc) std::printf("  ERROR: buildPC differs from pcFromACD\n");
    uint32_t acdSum = 0, eacdSum = 0;
    for (int o = 0; o < kOctants; ++o) {
        acdSum = vr::crc32Of(acd[o], acdSum);
        eacdSum = vr::crc32Of(eacd[o].data(), eacd[o].bytes(), eacdSum);
    }
    std::printf("  CRC-32:      labels %08x   PC %08x   ACD %08x   EACD %08x\n", vr::crc32Of(r.label),
                vr::crc32Of(pc), acdSum, eacdSum);

    // Mean guaranteed leap from a sample in each voxel, in voxels of the max norm (the farthest a sample in v can
    // move and stay in the box): PC r; ACD k - 1; EACD ext_a - 1 along axis a and min_a ext_a - 1 along the
    // diagonal; for a ray along +x and one along (+1, +1, +1), both in octant 0.
    double pcSum = 0, acdLeaps = 0, eacdX = 0, eacdDiagonal = 0;
    for (std::size_t v = 0; v < pc.size(); ++v) {
        pcSum += pc[v];
        acdLeaps += acd[0][v] - 1;
        const Extents e = eacd[0][v];
        eacdX += e[0] - 1;
        eacdDiagonal += std::min({e[0], e[1], e[2]}) - 1;
    }
    const double n = double(pc.size());
    std::printf("  mean leap (voxels): along +x  PC %.2f  ACD %.2f  EACD %.2f;  along (1,1,1)  PC %.2f  ACD %.2f  "
                "EACD %.2f\n",
                pcSum / n, acdLeaps / n, eacdX / n, pcSum / n, acdLeaps / n, eacdDiagonal / n);
}

}  // namespace

int main(int argc, char** argv) try {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
        std::printf("usage: fields_bench [--repeat N] [N | NXxNYxNZ | DATASET.raw.gz ...]\n"
                    "  N, NXxNYxNZ: constant and random-blocky regions of that size (default: 128 256)\n"
                    "  DATASET.raw.gz: a file of the datasets folder, classified with its manifest TF\n"
                    "  --repeat N: keep the fastest of N runs of every build\n");
        return 0;
    }
    int repeat = 1;
    if (args.size() >= 2 && args[0] == "--repeat") {
        repeat = std::max(1, std::atoi(args[1].c_str()));
        args.erase(args.begin(), args.begin() + 2);
    }
    if (args.empty()) args = {"128", "256"};
    std::printf("threads: %d (TBB)\n", tbb::info::default_concurrency());
    for (const std::string& arg : args) {
        if (arg.find(".raw") != std::string::npos) {
            run(arg.substr(0, arg.find('_', arg.find('_') + 1)), datasetRegions(arg), repeat);
            continue;
        }
        Vec3i d;
        const int fields = std::sscanf(arg.c_str(), "%dx%dx%d", &d.x, &d.y, &d.z);
        if (fields == 1) d = {d.x, d.x, d.x};
        if ((fields != 1 && fields != 3) || minComponent(d) < 1) {
            std::fprintf(stderr, "fields_bench: bad argument '%s' (want --repeat N, N, NXxNYxNZ or a dataset file)\n",
                         arg.c_str());
            return 1;
        }
        run("constant", constantVolume(d), repeat);
        run("random-blocky", blockyVolume(d), repeat);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "fields_bench: %s\n", e.what());
    return 1;
}
