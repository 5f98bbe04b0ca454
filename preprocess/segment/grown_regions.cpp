#include "preprocess/segment/grown_regions.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "core/errors.h"
#include "preprocess/segment/footprint_ranges.h"
#include "preprocess/segment/mixed_neighbourhoods.h"
#include "preprocess/segment/normal_classes.h"

namespace vr {
namespace {

// Voxels that can join no region: their own footprint spreads beyond T_o, or they sit where normals mix.
std::vector<uint8_t> borderVoxels(const Vec3i& dims, const FootprintRanges& footprints,
                                  const ClassificationSpread& spread, double threshold, const NormalClasses& normals) {
    std::vector<uint8_t> border =
        normals.used()
            ? mixedNeighbourhoods(dims, [&](std::size_t a, std::size_t b) { return normals.alike(a, b); })
            : std::vector<uint8_t>(footprints.lo.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, border.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        float lastLo = 1, lastHi = 0;  // an empty interval: never a footprint's
        bool lastAlike = false;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (border[i]) continue;
            // Neighbours often share their footprint's range (air, flat tissue): ask once per run of them.
            if (footprints.lo[i] != lastLo || footprints.hi[i] != lastHi) {
                lastLo = footprints.lo[i], lastHi = footprints.hi[i];
                lastAlike = spread.alike(lastLo, lastHi, threshold);
            }
            border[i] = !lastAlike;
        }
    });
    return border;
}

}  // namespace

void growPostClassifiedRegions(const ClassifiedVolume& classified, const SegmentationParams& params,
                               const std::vector<float>& scalars, const ClassificationSpread& spread, Regions& regions) {
    const Vec3i d = classified.grid.dims;
    const std::size_t n = voxelCount(d);
    if (n >= std::numeric_limits<uint32_t>::max())
        throw InputError("segmentation: " + std::to_string(n) + " voxels; at most 2^32 - 1 are supported");
    if (scalars.size() != n) throw InputError("segmentation: the scalars do not match the classified volume");
    const RegionKeyer keyer(classified, params);  // checks the thresholds
    const NormalClasses normals(keyer, n);
    const FootprintRanges footprints = footprintRanges(d, scalars);
    const double threshold = params.opacityThreshold;
    const std::vector<uint8_t> border = borderVoxels(d, footprints, spread, threshold, normals);

    constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();
    regions.dims = d;
    regions.label.assign(n, kUnset);
    std::vector<uint32_t>& label = regions.label;
    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y);
    std::vector<uint32_t> queue;
    uint32_t count = 0;
    // Every voxel before the seed is labelled, so the seed is its region's first voxel: labels in first-voxel order.
    for (std::size_t seed = 0; seed < n; ++seed) {
        if (label[seed] != kUnset) continue;
        const uint32_t id = count++;
        label[seed] = id;
        if (border[seed]) continue;
        float lo = footprints.lo[seed], hi = footprints.hi[seed];
        // The interval only widens as voxels join, so a voxel refused once would be refused again: each voxel is
        // asked at most once per neighbour that joins a region.
        const auto consider = [&](std::size_t u) {
            if (label[u] != kUnset || border[u] || !normals.alike(seed, u)) return;
            const float uLo = footprints.lo[u], uHi = footprints.hi[u];
            if (uLo < lo || uHi > hi) {
                const float wideLo = std::min(lo, uLo), wideHi = std::max(hi, uHi);
                if (!spread.alike(wideLo, wideHi, threshold)) return;
                lo = wideLo, hi = wideHi;
            }
            label[u] = id;
            queue.push_back(uint32_t(u));
        };
        queue.assign(1, uint32_t(seed));
        for (std::size_t head = 0; head < queue.size(); ++head) {
            const std::size_t v = queue[head];
            const std::size_t x = v % nx, y = v / nx % std::size_t(d.y), z = v / slice;
            if (x > 0) consider(v - 1);
            if (x + 1 < nx) consider(v + 1);
            if (y > 0) consider(v - nx);
            if (y + 1 < std::size_t(d.y)) consider(v + nx);
            if (z > 0) consider(v - slice);
            if (z + 1 < std::size_t(d.z)) consider(v + slice);
        }
    }
    regions.count = count;
}

}  // namespace vr
