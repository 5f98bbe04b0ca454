#include "volrender/cmd/render_stats.h"

#include <algorithm>
#include <numeric>

namespace vr {

nlohmann::json viewStatistics(const RenderResult& result, const std::vector<UploadedResource>& uploads) {
    std::vector<uint32_t> sorted = result.iterations;
    std::sort(sorted.begin(), sorted.end());
    const double rays = double(std::max<std::size_t>(1, sorted.size()));
    const double iterations = std::accumulate(sorted.begin(), sorted.end(), 0.0);
    const double samples = std::accumulate(result.samples.begin(), result.samples.end(), 0.0);
    nlohmann::json uploaded = nlohmann::json::object();
    std::size_t total = 0;
    for (const auto& u : uploads) {
        uploaded[u.name] = u.bytes;
        total += u.bytes;
    }
    return {{"deviceMs", result.deviceMilliseconds},
            {"wallMs", result.wallMilliseconds},
            {"iterationsPerRay",
             {{"mean", iterations / rays},
              {"p95", sorted.empty() ? 0u : sorted[std::min(sorted.size() - 1, std::size_t(0.95 * sorted.size()))]},
              {"max", sorted.empty() ? 0u : sorted.back()}}},
            {"samplesRepresented", {{"total", samples}, {"meanPerRay", samples / rays}}},
            {"uploadedBytes", uploaded},
            {"uploadedBytesTotal", total}};
}

}  // namespace vr
