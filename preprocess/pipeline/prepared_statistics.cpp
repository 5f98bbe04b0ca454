#include "preprocess/pipeline/prepared_statistics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <array>

namespace vr {
using json = nlohmann::json;

namespace {

// Means of the N distances get(element) gives, over a field (a vector or an ExtentField), in parallel: one pass,
// each element read (an ExtentField's box decoded) once.
template <std::size_t N, typename Field, typename Get>
std::array<double, N> meansOf(const Field& v, Get get) {
    using Sums = std::array<double, N>;
    if (v.empty()) return {};
    Sums sum = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, v.size()), Sums{},
        [&](const tbb::blocked_range<std::size_t>& r, Sums s) {
            std::array<uint64_t, N> local{};  // exact: at most 255 per voxel
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                const auto x = get(v[i]);
                for (std::size_t a = 0; a < N; ++a) local[a] += x[a];
            }
            for (std::size_t a = 0; a < N; ++a) s[a] += double(local[a]);
            return s;
        },
        [](Sums a, const Sums& b) {
            for (std::size_t i = 0; i < N; ++i) a[i] += b[i];
            return a;
        });
    for (double& m : sum) m /= double(v.size());
    return sum;
}

double meanOf(const std::vector<uint8_t>& distances) {
    return meansOf<1>(distances, [](uint8_t d) { return std::array<uint8_t, 1>{d}; })[0];
}

template <typename T>
std::size_t bytesOf(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

}  // namespace

json preparedStatistics(const PreparedVolume& p, const std::vector<StageTime>& stages) {
    const std::size_t voxels = p.grid().voxels();
    json s;
    s["voxels"] = voxels;
    s["regions"] = p.regions.count;
    s["meanRegionSize"] = p.regions.count ? double(voxels) / p.regions.count : 0.0;

    json leaps = json::object();
    const DistanceFields& f = p.fields;
    if (f.hasPC()) leaps["pcMeanRadius"] = meanOf(f.pc);
    if (f.hasACD()) {
        json edges = json::array();
        for (int o = 0; o < kOctants; ++o) edges.push_back(meanOf(f.acd[o]));
        leaps["acdMeanEdge"] = edges;
    }
    if (f.hasEACD()) {
        json extents = json::array();
        for (int o = 0; o < kOctants; ++o) extents.push_back(meansOf<3>(f.eacd[o], [](const Extents& e) { return e; }));
        leaps["eacdMeanExtent"] = extents;
    }
    s["leaps"] = leaps;

    const FieldBytes fieldBytes = fieldBytesOf(f);
    // As the prepared file holds them: the scalars in their own type, the table as four floats per entry.
    s["bytes"] = {{"scalars", voxels * scalarBytes(p.scalars.sourceType)},
                  {"table", p.classification.table.size() * 4 * sizeof(float)},
                  {"labels", bytesOf(p.regions.label)},
                  {"pc", fieldBytes.pc}, {"acd", fieldBytes.acd}, {"eacd", fieldBytes.eacd}};
    s["eacdCode"] = extentCodeName(f.eacdCode());
    json seconds = json::object(), cpuSeconds = json::object();
    for (const StageTime& t : stages) {
        seconds[t.stage] = t.seconds;
        cpuSeconds[t.stage] = t.cpuSeconds;
    }
    s["seconds"] = seconds;
    s["cpuSeconds"] = cpuSeconds;
    return s;
}

}  // namespace vr
