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

// The steps' shares of the time, as a shaded 512^3 CT took them on 2 cores: the footprints' ranges until
// kFootprintsEnd (1.1 s), the border voxels until kBordersEnd (3.55 s, kNormalsShare of it their normal classes), the
// growth the rest (1.1 s).
constexpr double kFootprintsEnd = 0.19, kBordersEnd = 0.81, kNormalsShare = 0.87;

// Labels kBorderCell where a voxel can join no region: its own footprint spreads beyond T_o, or normals mix around it
// (normals in use); kUnsetCell elsewhere. `progress` hears the normal classes as they are keyed, then the mixed
// neighbourhoods and the labels as half the rest each.
void markBorderVoxels(const Vec3i& dims, const std::vector<EntryRange>& footprints,
                      const ClassificationSpread& spread, double threshold, const RegionKeyer& keyer,
                      const ClassifiedVoxels& voxels, std::vector<uint32_t>& label, const Progress& progress) {
    const NormalClasses normals(keyer, label.size(), progressPart(progress, 0, kNormalsShare));
    // Label maps: a voxel beside another label is a border voxel too, as its footprint reads that label's scalars
    // and its gradient that label's indicator.
    const std::vector<uint8_t> mixed =
        normals.used() || voxels.labelled()
            ? mixedNeighbourhoods(dims, [&](std::size_t a, std::size_t b) {
                  return normals.alike(a, b) && voxels.label(a) == voxels.label(b);
              })
            : std::vector<uint8_t>(footprints.size());
    reportProgress(progress, kNormalsShare + (1 - kNormalsShare) / 2);
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
            label[i] = mixed[i] || !lastAlike ? kBorderCell : kUnsetCell;
        }
    });
}

}  // namespace

uint32_t growRegions(const Vec3i& d, const std::vector<EntryRange>& ranges, const ClassificationSpread& spread,
                     double threshold, std::vector<uint32_t>& label, const Progress& progress) {
    const std::size_t n = label.size();
    const std::size_t nx = std::size_t(d.x), slice = nx * std::size_t(d.y);
    std::vector<uint32_t> pending;  // joined, neighbours not yet considered
    uint32_t count = 0;
    // Every cell before the seed is labelled, so the seed is its region's first cell: labels in first-cell order.
    // Cells labelled so far, for `progress`: a seed's region may take most of the volume (the air around a CT).
    std::size_t labelled = 0;
    const auto labelCell = [&](std::size_t u, uint32_t id) {
        label[u] = id;
        if (progress && ++labelled % (1u << 20) == 0) progress(double(labelled) / double(n));
    };
    for (std::size_t seed = 0; seed < n; ++seed) {
        if (label[seed] < kBorderCell) continue;
        const bool border = label[seed] == kBorderCell;
        const uint32_t id = count++;
        labelCell(seed, id);
        if (border) continue;
        EntryRange range = ranges[seed];
        // The range only widens as cells join, so a cell refused once would be refused again: each cell is asked at
        // most once per neighbour that joins a region.
        const auto consider = [&](std::size_t u) {
            if (label[u] != kUnsetCell) return;
            const EntryRange f = ranges[u];
            if (f.lo < range.lo || f.hi > range.hi) {
                const EntryRange wide{std::min(range.lo, f.lo), std::max(range.hi, f.hi)};
                if (!spread.alikeEntries(wide.lo, wide.hi, threshold)) return;
                range = wide;
            }
            labelCell(u, id);
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
    return count;
}

void growPostClassifiedRegions(const ClassifiedVoxels& voxels, const SegmentationParams& params,
                               const std::vector<float>& scalars, const ClassificationSpread& spread,
                               Regions& regions, const Progress& progress) {
    const Vec3i d = voxels.grid().dims;
    const std::size_t n = voxelCount(d);
    if (n >= kBorderCell)
        throw InputError("segmentation: " + std::to_string(n) + " voxels; at most 2^32 - 2 are supported");
    if (scalars.size() != n) throw InputError("segmentation: the scalars do not match the classified volume");
    const RegionKeyer keyer(voxels, params);  // checks the thresholds
    const std::vector<EntryRange> footprints = footprintRanges(d, scalars, spread);
    reportProgress(progress, kFootprintsEnd);
    regions.dims = d;
    regions.label.resize(n);
    markBorderVoxels(d, footprints, spread, params.opacityThreshold, keyer, voxels, regions.label,
                     progressPart(progress, kFootprintsEnd, kBordersEnd));
    reportProgress(progress, kBordersEnd);
    // Normals and labels need no test as regions grow: a voxel that is not a border voxel has the normal key and the
    // label of all its neighbours, so the whole region has the seed's.
    regions.count = growRegions(d, footprints, spread, params.opacityThreshold, regions.label,
                                progressPart(progress, kBordersEnd, 1));
    reportProgress(progress, 1);
}

}  // namespace vr
