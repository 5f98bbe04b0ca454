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

constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();
constexpr uint32_t kBorder = kUnset - 1;  // a border voxel before its label: joins no region

// Labels kBorder where a voxel can join no region: its own footprint spreads beyond T_o, or normals mix around it
// (normals in use); kUnset elsewhere.
void markBorderVoxels(const Vec3i& dims, const std::vector<EntryRange>& footprints,
                      const ClassificationSpread& spread, double threshold, const RegionKeyer& keyer,
                      const ClassifiedVoxels& voxels, std::vector<uint32_t>& label) {
    const NormalClasses normals(keyer, label.size());
    // Label maps: a voxel beside another label is a border voxel too, as its footprint reads that label's scalars
    // and its gradient that label's indicator.
    const std::vector<uint8_t> mixed =
        normals.used() || voxels.labelled()
            ? mixedNeighbourhoods(dims, [&](std::size_t a, std::size_t b) {
                  return normals.alike(a, b) && voxels.label(a) == voxels.label(b);
              })
            : std::vector<uint8_t>(footprints.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, label.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        EntryRange last{1, 0};  // an empty range: never a footprint's
        bool lastAlike = false;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            // Neighbours often share their footprint's range (air, flat tissue): ask once per run of them.
            const EntryRange f = footprints[i];
            if (!mixed[i] && (f.lo != last.lo || f.hi != last.hi)) {
                last = f;
                lastAlike = spread.alikeEntries(f.lo, f.hi, threshold);
            }
            label[i] = mixed[i] || !lastAlike ? kBorder : kUnset;
        }
    });
}

}  // namespace

void growPostClassifiedRegions(const ClassifiedVoxels& voxels, const SegmentationParams& params,
                               const std::vector<float>& scalars, const ClassificationSpread& spread, Regions& regions) {
    const Vec3i d = voxels.grid().dims;
    const std::size_t n = voxelCount(d);
    if (n >= kBorder)
        throw InputError("segmentation: " + std::to_string(n) + " voxels; at most 2^32 - 2 are supported");
    if (scalars.size() != n) throw InputError("segmentation: the scalars do not match the classified volume");
    const RegionKeyer keyer(voxels, params);  // checks the thresholds
    const std::vector<EntryRange> footprints = footprintRanges(d, scalars, spread);
    const double threshold = params.opacityThreshold;
    regions.dims = d;
    regions.label.resize(n);
    std::vector<uint32_t>& label = regions.label;
    markBorderVoxels(d, footprints, spread, threshold, keyer, voxels, label);

    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y);
    std::vector<uint32_t> pending;  // joined, neighbours not yet considered
    uint32_t count = 0;
    // Every voxel before the seed is labelled, so the seed is its region's first voxel: labels in first-voxel order.
    for (std::size_t seed = 0; seed < n; ++seed) {
        if (label[seed] < kBorder) continue;
        const bool border = label[seed] == kBorder;
        const uint32_t id = count++;
        label[seed] = id;
        if (border) continue;
        EntryRange range = footprints[seed];
        // The range only widens as voxels join, so a voxel refused once would be refused again: each voxel is
        // asked at most once per neighbour that joins a region. Normals and labels need no test: a voxel that is
        // not a border voxel has the normal key and the label of all its neighbours, so the whole region has the
        // seed's.
        const auto consider = [&](std::size_t u) {
            if (label[u] != kUnset) return;
            const EntryRange f = footprints[u];
            if (f.lo < range.lo || f.hi > range.hi) {
                const EntryRange wide{std::min(range.lo, f.lo), std::max(range.hi, f.hi)};
                if (!spread.alikeEntries(wide.lo, wide.hi, threshold)) return;
                range = wide;
            }
            label[u] = id;
            pending.push_back(uint32_t(u));
        };
        // Depth first, the +x neighbour taken next: the walk follows rows through memory.
        pending.assign(1, uint32_t(seed));
        while (!pending.empty()) {
            const std::size_t v = pending.back();
            pending.pop_back();
            const std::size_t x = v % nx, y = v / nx % std::size_t(d.y), z = v / slice;
            if (z > 0) consider(v - slice);
            if (z + 1 < std::size_t(d.z)) consider(v + slice);
            if (y > 0) consider(v - nx);
            if (y + 1 < std::size_t(d.y)) consider(v + nx);
            if (x > 0) consider(v - 1);
            if (x + 1 < nx) consider(v + 1);
        }
    }
    regions.count = count;
}

}  // namespace vr
