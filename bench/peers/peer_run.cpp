#include "bench/peers/peer_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vr {
namespace fs = std::filesystem;

static double nearestRank(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const auto rank = std::size_t(std::ceil(q * double(v.size())));
    return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

double PeerRun::medianMs() const {
    if (ms.empty()) return 0;
    std::vector<double> v = ms;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double PeerRun::p95Ms() const { return nearestRank(ms, 0.95); }

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

PeerRun runViews(const std::string& peer, const PeerScene& scene, const fs::path& outDir, const RenderView& render) {
    PeerRun run;
    run.peer = peer;
    const fs::path folder = outDir / peer;
    fs::create_directories(folder);
    Image image(scene.options.width, scene.options.height);
    render(0, image);  // warm-up: contexts, uploads, shader compiles, caches
    for (std::size_t i = 0; i < scene.views.size(); ++i) {
        image = Image(scene.options.width, scene.options.height);
        run.ms.push_back(render(i, image));
        char name[32];
        std::snprintf(name, sizeof name, "view_%03zu", i);
        run.images.push_back(folder / (std::string(name) + ".exr"));
        writeImage(run.images.back(), image);
        writeImage(folder / (std::string(name) + ".png"), image);
        std::fprintf(stderr, "  %s view %zu: %.1f ms\n", peer.c_str(), i, run.ms.back());
    }
    return run;
}

}  // namespace vr
