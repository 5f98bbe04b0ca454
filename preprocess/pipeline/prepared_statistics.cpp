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

// The mean box of an EACD octant. A coded field's codes are counted first (log16: each axis' 5-bit index; joint8:
// the byte), in one parallel pass over its bytes, and each code is decoded once: a decode per voxel and octant took
// a fifth of volprep's time on a 512^3 CT.
std::array<double, 3> meanExtents(const ExtentField& field) {
    const std::size_t n = field.size();
    const uint8_t* bytes = field.data();
    if (n == 0) return {};
    if (field.code() == ExtentCode::Exact) return meansOf<3>(field, [](const Extents& e) { return e; });
    // Bins: log16's three axes of 32 indices each, or joint8's 256 bytes.
    using Counts = std::array<uint64_t, 256>;
    const bool log16 = field.code() == ExtentCode::Log16;
    const Counts counts = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n), Counts{},
        [&](const tbb::blocked_range<std::size_t>& r, Counts c) {
            if (log16)
                for (std::size_t i = r.begin(); i < r.end(); ++i) {
                    const unsigned code = bytes[2 * i] | unsigned(bytes[2 * i + 1]) << 8;
                    ++c[code & 31];
                    ++c[32 + (code >> 5 & 31)];
                    ++c[64 + (code >> 10 & 31)];
                }
            else
                for (std::size_t i = r.begin(); i < r.end(); ++i) ++c[bytes[i]];
            return c;
        },
        [](Counts a, const Counts& b) {
            for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
            return a;
        });
    const ExtentTable& table = extentDecodeTable(field.code());
    std::array<double, 3> sums{};
    for (int a = 0; a < 3; ++a)
        for (unsigned code = 0; code < (log16 ? 32u : 256u); ++code)
            sums[a] += double(counts[log16 ? 32 * a + code : code]) * table[code][a];
    for (double& s : sums) s /= double(n);
    return sums;
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
        for (int o = 0; o < kOctants; ++o) extents.push_back(meanExtents(f.eacd[o]));
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
