#include "preprocess/cmd/summary.h"

#include "tools/peak_resident.h"

namespace vr {

namespace {

double megabytes(double bytes) { return bytes / (1024.0 * 1024.0); }

}  // namespace

void printSummary(std::FILE* out, const std::filesystem::path& output, const PreparedVolume& p,
                  const std::vector<StageTime>& stages) {
    const nlohmann::json& s = p.meta.statistics;
    const Vec3i n = p.grid().dims;
    std::fprintf(out, "wrote %s (%.1f MiB)\n", output.c_str(), megabytes(double(std::filesystem::file_size(output))));
    std::fprintf(out, "  voxels   %zu (%d x %d x %d)\n", p.grid().voxels(), n.x, n.y, n.z);
    std::fprintf(out, "  regions  %u (mean %.1f voxels per region)\n", p.regions.count,
                 s["meanRegionSize"].get<double>());

    const nlohmann::json& leaps = s["leaps"];
    if (leaps.contains("pcMeanRadius"))
        std::fprintf(out, "  mean PC radius    %.2f voxels\n", leaps["pcMeanRadius"].get<double>());
    if (leaps.contains("acdMeanEdge")) {
        std::fprintf(out, "  mean ACD edge     octants 0-7:");
        for (double e : leaps["acdMeanEdge"]) std::fprintf(out, " %.2f", e);
        std::fprintf(out, "\n");
    }
    if (leaps.contains("eacdMeanExtent")) {
        std::fprintf(out, "  mean EACD extents octants 0-7 (x,y,z; %s code):",
                     std::string(extentCodeName(p.fields.eacdCode())).c_str());
        for (const auto& e : leaps["eacdMeanExtent"])
            std::fprintf(out, " (%.2f,%.2f,%.2f)", e[0].get<double>(), e[1].get<double>(), e[2].get<double>());
        std::fprintf(out, "\n");
    }

    std::fprintf(out, "  seconds  ");
    double total = 0;
    for (const StageTime& t : stages) {
        std::fprintf(out, " %s %.3f", t.stage.c_str(), t.seconds);
        total += t.seconds;
    }
    std::fprintf(out, "  (total %.3f)\n", total);

    std::fprintf(out, "  MiB      ");
    for (const auto& [chunk, bytes] : s["bytes"].items())
        if (bytes.get<std::size_t>() > 0) std::fprintf(out, " %s %.1f", chunk.c_str(), megabytes(bytes.get<double>()));
    std::fprintf(out, "  (peak resident %.1f)\n", megabytes(double(peakResidentBytes())));
}

}  // namespace vr
