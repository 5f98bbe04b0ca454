// Distance-field build times (PC, ACD x 8, EACD x 8) and mean leap lengths, on constant and random-blocky volumes.
// Usage: fields_bench [N | NXxNYxNZ ...]   (default: 128 256, i.e. 128^3 and 256^3)
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>

#include "preprocess/fields/build_fields.h"

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

void run(const std::string& name, const Regions& r) {
    Timer t;
    const std::vector<uint8_t> pc = buildPC(r);
    const std::string pcTime = t.done();

    t = Timer();
    std::array<std::vector<uint8_t>, kOctants> acd;
    for (int o = 0; o < kOctants; ++o) acd[o] = buildACD(r, o);
    const std::string acdTime = t.done();

    t = Timer();
    const std::array<EACDField, kOctants> eacd = buildEACD(r, acd);
    const std::string eacdTime = t.done();

    // Mean guaranteed leap from a sample in each voxel, in voxels of the max norm (the farthest a sample in v can
    // move and stay in the box): PC r; ACD k - 1; EACD ext_a - 1 along axis a and min_a ext_a - 1 along the
    // diagonal; for a ray along +x and one along (+1, +1, +1), both in octant 0.
    double pcSum = 0, acdSum = 0, eacdX = 0, eacdDiagonal = 0;
    for (std::size_t v = 0; v < pc.size(); ++v) {
        pcSum += pc[v];
        acdSum += acd[0][v] - 1;
        const auto& e = eacd[0][v];
        eacdX += e[0] - 1;
        eacdDiagonal += std::min({e[0], e[1], e[2]}) - 1;
    }
    const double n = double(pc.size());
    std::printf("%-14s %dx%dx%d\n  PC %s   ACD x8 %s   EACD x8 %s\n", name.c_str(), r.dims.x, r.dims.y, r.dims.z,
                pcTime.c_str(), acdTime.c_str(), eacdTime.c_str());
    std::printf("  mean leap (voxels): along +x  PC %.2f  ACD %.2f  EACD %.2f;  along (1,1,1)  PC %.2f  ACD %.2f  "
                "EACD %.2f\n",
                pcSum / n, acdSum / n, eacdX / n, pcSum / n, acdSum / n, eacdDiagonal / n);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<Vec3i> sizes;
    for (int i = 1; i < argc; ++i) {
        Vec3i d;
        const int fields = std::sscanf(argv[i], "%dx%dx%d", &d.x, &d.y, &d.z);
        if (fields == 1) d = {d.x, d.x, d.x};
        if ((fields != 1 && fields != 3) || minComponent(d) < 1) {
            std::fprintf(stderr, "fields_bench: bad size '%s' (want N or NXxNYxNZ)\n", argv[i]);
            return 1;
        }
        sizes.push_back(d);
    }
    if (sizes.empty()) sizes = {{128, 128, 128}, {256, 256, 256}};
    std::printf("threads: %d (TBB)\n", tbb::info::default_concurrency());
    for (const Vec3i& d : sizes) {
        run("constant", constantVolume(d));
        run("random-blocky", blockyVolume(d));
    }
    return 0;
}
