#include "volrender/cmd/render_stats.h"

#include <algorithm>
#include <numeric>

#include "render/count_percentile.h"

namespace vr {

nlohmann::json viewStatistics(const RenderResult& result, const std::vector<UploadedResource>& uploads) {
    nlohmann::json uploaded = nlohmann::json::object();
    std::size_t total = 0;
    for (const auto& u : uploads) {
        uploaded[u.name] = uploaded.value(u.name, std::size_t(0)) + u.bytes;
        total += u.bytes;
    }
    nlohmann::json stats{{"deviceMs", result.deviceMilliseconds},
                         {"wallMs", result.wallMilliseconds},
                         {"uploadedBytes", uploaded},
                         {"uploadedBytesTotal", total}};
    const std::vector<uint32_t>& counts = result.iterations;
    if (counts.empty()) return stats;  // rendered without ray counts
    const std::vector<uint32_t> percentiles = countPercentiles(counts, {0.95, 1.0});
    const double rays = double(counts.size());
    const double iterations = std::accumulate(counts.begin(), counts.end(), 0.0);
    const double samples = std::accumulate(result.samples.begin(), result.samples.end(), 0.0);
    stats["iterationsPerRay"] = {{"mean", iterations / rays}, {"p95", percentiles[0]}, {"max", percentiles[1]}};
    stats["samplesRepresented"] = {{"total", samples}, {"meanPerRay", samples / rays}};
    return stats;
}

nlohmann::json uploadStatistics(const GpuVolume& volume, double milliseconds) {
    auto triple = [](const Vec3i& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    nlohmann::json bytes = nlohmann::json::object(), bricks = nlohmann::json::array();
    for (const Brick& b : volume.bricks().bricks())
        bricks.push_back({{"lo", triple(b.lo)}, {"hi", triple(b.hi)}, {"imageLo", triple(b.imageLo)},
                          {"imageDims", triple(b.imageDims)}, {"bytes", nlohmann::json::object()}});
    for (const UploadedResource& u : volume.uploads()) {
        bytes[u.name] = bytes.value(u.name, std::size_t(0)) + u.bytes;
        bricks[u.brick]["bytes"][u.name] = u.bytes;
    }
    // Per voxel of the volume: what each resource costs the device (a table's bytes spread over the voxels too).
    const double voxels = double(std::max<std::size_t>(1, volume.grid().voxels()));
    nlohmann::json perVoxel = nlohmann::json::object();
    for (const auto& [name, b] : bytes.items()) perVoxel[name] = b.get<double>() / voxels;
    return {{"milliseconds", milliseconds},
            {"bytes", bytes},
            {"bytesPerVoxel", perVoxel},
            {"bytesPerVoxelTotal", double(volume.uploadedBytes()) / voxels},
            {"bytesTotal", volume.uploadedBytes()},
            {"brickCounts", triple(volume.bricks().counts())},
            {"bricks", bricks}};
}

}  // namespace vr
