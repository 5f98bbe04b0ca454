#include "preprocess/fields/axial_runs.h"

#include <tbb/parallel_for.h>

#include "core/distance_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

// One x-row of runs along x, scanned toward -sign: each voxel extends its neighbour's run (a serial chain).
void runRowAlongX(const uint32_t* label, uint8_t* run, int nx, int sign) {
    int previous = 0;
    for (int i = 0; i < nx; ++i) {
        const int x = scanCoord(i, nx, sign);
        previous = i > 0 && label[x] == label[x + sign] ? std::min(previous + 1, kDistanceCap) : 1;
        run[x] = uint8_t(previous);
    }
}

// One x-row of runs along y or z from the row one step toward the sign (`next`), null at the border: every
// voxel is independent, 16 at a time.
void runRowAcross(const uint32_t* label, const uint32_t* nextLabel, const uint8_t* nextRun, uint8_t* run, int nx) {
    if (!nextLabel) {
        std::fill(run, run + nx, uint8_t(1));
        return;
    }
    forEachLane(nx, [&](std::size_t k, auto lanes) {
        using T = decltype(lanes);
        // A voxel of another region than its neighbour starts a run of 1: 0 & mask, plus one.
        store(run + k, plusOne(T(load(nextRun + k, lanes) & equalLabels(label + k, nextLabel + k, lanes))));
    });
}

}  // namespace

std::vector<uint8_t> axialRuns(const Regions& regions, int axis, int sign) {
    requireLabelPerVoxel(regions, "axialRuns");
    const Vec3i& n = regions.dims;
    std::vector<uint8_t> run(voxelCount(n));
    if (run.empty()) return run;
    const uint32_t* label = regions.label.data();
    uint8_t* out = run.data();
    if (axis == 0) {
        tbb::parallel_for(0, n.z, [&](int z) {
            for (int y = 0; y < n.y; ++y) {
                const std::size_t row = linearIndex(n, 0, y, z);
                runRowAlongX(label + row, out + row, n.x, sign);
            }
        });
        return run;
    }
    // Rows across y depend on the previous row of their slice; rows across z on the previous slice's row.
    const std::ptrdiff_t step = std::ptrdiff_t(sign) * (axis == 1 ? n.x : std::ptrdiff_t(n.x) * n.y);
    const int lines = axis == 1 ? n.z : n.y, length = n[axis];
    tbb::parallel_for(0, lines, [&](int line) {
        for (int i = 0; i < length; ++i) {
            const int c = scanCoord(i, length, sign);
            const std::size_t v = axis == 1 ? linearIndex(n, 0, c, line) : linearIndex(n, 0, line, c);
            const bool border = i == 0;
            runRowAcross(label + v, border ? nullptr : label + v + step, border ? nullptr : out + v + step, out + v,
                         n.x);
        }
    });
    return run;
}

AxialRuns::AxialRuns(const Regions& regions) : regions_(regions) { requireLabelPerVoxel(regions, "AxialRuns"); }

const std::vector<uint8_t>& AxialRuns::get(int axis, int sign) {
    std::vector<uint8_t>& run = runs_[2 * axis + (sign < 0)];
    if (run.empty()) run = axialRuns(regions_, axis, sign);
    return run;
}

void AxialRuns::computeAll() {
    tbb::parallel_for(0, 6, [&](int i) {
        if (runs_[i].empty()) runs_[i] = axialRuns(regions_, i / 2, i % 2 ? -1 : 1);
    });
}

}  // namespace vr
