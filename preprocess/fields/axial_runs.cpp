#include "preprocess/fields/axial_runs.h"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "core/distance_fields.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

// run[v] from its neighbour w = v + sign * e_axis, already done.
inline uint8_t extendRun(uint32_t labelV, uint32_t labelW, uint8_t runW) {
    return labelV == labelW ? uint8_t(std::min(runW + 1, kDistanceCap)) : uint8_t(1);
}

// One x-row of runs along y or z: `next` is the row one step toward `sign`, or null at the border.
void runRow(const uint32_t* label, const uint32_t* nextLabel, const uint8_t* nextRun, uint8_t* run, int nx) {
    if (!nextLabel) {
        std::fill(run, run + nx, uint8_t(1));
        return;
    }
    for (int x = 0; x < nx; ++x) run[x] = extendRun(label[x], nextLabel[x], nextRun[x]);
}

}  // namespace

std::vector<uint8_t> axialRuns(const Regions& regions, int axis, int sign) {
    requireLabelPerVoxel(regions, "axialRuns");
    const Vec3i& n = regions.dims;
    std::vector<uint8_t> run(voxelCount(n));
    if (run.empty()) return run;
    const uint32_t* label = regions.label.data();
    uint8_t* out = run.data();
    const std::size_t plane = std::size_t(n.x) * n.y;
    if (axis == 0) {
        tbb::parallel_for(0, n.z, [&](int z) {
            for (int y = 0; y < n.y; ++y) {
                const std::size_t row = linearIndex(n, 0, y, z);
                for (int i = 0; i < n.x; ++i) {
                    const std::size_t v = row + scanCoord(i, n.x, sign);
                    out[v] = i == 0 ? uint8_t(1) : extendRun(label[v], label[v + sign], out[v + sign]);
                }
            }
        });
    } else if (axis == 1) {
        tbb::parallel_for(0, n.z, [&](int z) {
            for (int i = 0; i < n.y; ++i) {
                const std::size_t v = linearIndex(n, 0, scanCoord(i, n.y, sign), z);
                const std::ptrdiff_t step = std::ptrdiff_t(sign) * n.x;
                const bool border = i == 0;
                runRow(label + v, border ? nullptr : label + v + step, border ? nullptr : out + v + step, out + v, n.x);
            }
        });
    } else {
        tbb::parallel_for(0, n.y, [&](int y) {
            for (int i = 0; i < n.z; ++i) {
                const std::size_t v = linearIndex(n, 0, y, scanCoord(i, n.z, sign));
                const std::ptrdiff_t step = std::ptrdiff_t(sign) * std::ptrdiff_t(plane);
                const bool border = i == 0;
                runRow(label + v, border ? nullptr : label + v + step, border ? nullptr : out + v + step, out + v, n.x);
            }
        });
    }
    return run;
}

}  // namespace vr
