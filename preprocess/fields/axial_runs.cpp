#include "preprocess/fields/axial_runs.h"

#include <tbb/parallel_for.h>

#include <cstring>

#include "core/distance_fields.h"
#include "preprocess/fields/byte_rows.h"
#include "preprocess/fields/scan_order.h"

namespace vr {

namespace {

#if defined(__SSE2__)
// Lane k gets lane k + sign * kLanes (the voxels scanned before it), 0 where that is outside the 16.
template <int kSign, int kLanes>
__m128i fromScannedBefore(__m128i v) {
    return kSign < 0 ? _mm_slli_si128(v, kLanes) : _mm_srli_si128(v, kLanes);
}

// One log step of the segmented count: r += r of kLanes before where no run starts in between; `joined` (no run
// starts in the lanes up to there, within the 16) widens likewise, with the lanes that have none before them.
template <int kSign, int kLanes>
void countStep(__m128i& r, __m128i& joined) {
    const __m128i ones = _mm_set1_epi8(-1), edge = _mm_xor_si128(ones, fromScannedBefore<kSign, kLanes>(ones));
    r = _mm_adds_epu8(r, _mm_and_si128(joined, fromScannedBefore<kSign, kLanes>(r)));
    joined = _mm_and_si128(joined, _mm_or_si128(fromScannedBefore<kSign, kLanes>(joined), edge));
}

// The runs of 16 voxels of a row whose neighbours toward the sign are all in the row, `carry` the run of the one
// next to the block: each voxel equal to its neighbour continues its run, counted in four log steps (saturating at
// 255, the cap) rather than along a chain of one voxel at a time.
template <int kSign>
void runBlock(const uint32_t* label, uint8_t* run, uint8_t carry) {
    const Bytes16 equal = equalLabels(label, label + kSign);
    __m128i joined, r = _mm_set1_epi8(1);
    std::memcpy(&joined, &equal, sizeof joined);
    countStep<kSign, 1>(r, joined);
    countStep<kSign, 2>(r, joined);
    countStep<kSign, 4>(r, joined);
    countStep<kSign, 8>(r, joined);
    r = _mm_adds_epu8(r, _mm_and_si128(joined, _mm_set1_epi8(char(carry))));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(run), r);
}
#endif

// One x-row of runs along x, scanned toward -sign: each voxel extends its neighbour's run.
void runRowAlongX(const uint32_t* label, uint8_t* run, int nx, int sign) {
    const auto one = [&](int i) {  // the i-th voxel of the scan, from its neighbour's run
        const int x = scanCoord(i, nx, sign);
        run[x] = i > 0 && label[x] == label[x + sign] ? uint8_t(std::min(run[x + sign] + 1, kDistanceCap)) : 1;
    };
    int i = 0;
    if (nx > 0) one(i++);  // the first has no neighbour: the blocks after it all have theirs
#if defined(__SSE2__)
    for (; i + 16 <= nx; i += 16) {
        if (sign < 0)
            runBlock<-1>(label + i, run + i, run[i - 1]);
        else
            runBlock<1>(label + nx - i - 16, run + nx - i - 16, run[nx - i]);
    }
#endif
    for (; i < nx; ++i) one(i);
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

void AxialRuns::computeAll(unsigned octants) {
    tbb::parallel_for(0, 6, [&](int i) {
        const int axis = i / 2, sign = i % 2 ? -1 : 1;
        if (read(octants, axis, sign) && runs_[i].empty()) runs_[i] = axialRuns(regions_, axis, sign);
    });
}

}  // namespace vr
