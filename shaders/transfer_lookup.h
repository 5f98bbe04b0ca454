// Where a scalar falls in the transfer table (core/scalar_classification.h), stated once: the CPU reference reads
// it in double, the casters in float (shared_language.h).
#ifndef VR_TRANSFER_LOOKUP_H
#define VR_TRANSFER_LOOKUP_H

#include "shared_language.h"

#ifdef __cplusplus
#include <cstddef>

namespace vr::device {
#endif

// The table coordinate t of scalar f: entry floor(t), and t - floor(t) the weight of the entry after it; clamped
// to [0, lastEntry] (a NaN goes to 0). An integer volume's table has a step of 1, so its voxels land on entries
// exactly.
VR_FUNCTION VR_REAL tableCoordinate(VR_REAL f, VR_REAL lo, VR_REAL inverseStep, VR_REAL lastEntry) {
    VR_REAL t = (f - lo) * inverseStep;
    return t > VR_REAL(0) ? (t < lastEntry ? t : lastEntry) : VR_REAL(0);
}

// The value between a and b at weight w of b: exactly a where b equals a, so a sample inside a region whose
// entries are all alike classifies bit for bit alike however it interpolates (docs/ALGORITHMS.md section 9).
VR_FUNCTION VR_REAL interpolate(VR_REAL a, VR_REAL b, VR_REAL w) { return a + (b - a) * w; }

// Trilinear interpolation of the corners cXYZ of a cell at fractions fx, fy, fz: x first, then y, then z, each an
// interpolate() of two values, so that equal corners give their value exactly and the result stays within the
// corners' range (for integer scalars): a trilinear sample looks up only entries that post-classified regions
// vouch for.
VR_FUNCTION VR_REAL trilinearBlend(VR_REAL c000, VR_REAL c100, VR_REAL c010, VR_REAL c110, VR_REAL c001, VR_REAL c101,
                                   VR_REAL c011, VR_REAL c111, VR_REAL fx, VR_REAL fy, VR_REAL fz) {
    return interpolate(interpolate(interpolate(c000, c100, fx), interpolate(c010, c110, fx), fy),
                          interpolate(interpolate(c001, c101, fx), interpolate(c011, c111, fx), fy), fz);
}

#ifdef __cplusplus
// A scalar's extinction and colour from a table with `lo`, `step`, and `sigma` and `colour` per entry
// (core/scalar_classification.h's TransferTable), in double: what the CPU reference and the classified volume take
// where the casters read their table buffer.
struct TableSample {
    double sigma;
    double colour[3];
};
// The entries around scalar f, i and j, and the weight w of j.
struct TableSpot {
    std::size_t i, j;
    double w;
};
template <typename Table>
TableSpot tableSpot(const Table& table, double f) {
    const double t = tableCoordinate(f, table.lo, 1 / table.step, double(table.size() - 1));
    const std::size_t i = std::size_t(t);
    return {i, i + 1 < table.size() ? i + 1 : i, t - double(i)};
}
template <typename Table>
TableSample lookUpTable(const Table& table, double f) {
    const TableSpot at = tableSpot(table, f);
    TableSample s{interpolate(table.sigma[at.i], table.sigma[at.j], at.w), {}};
    for (int a = 0; a < 3; ++a) s.colour[a] = interpolate(table.colour[at.i][a], table.colour[at.j][a], at.w);
    return s;
}
// The extinction alone, as lookUpTable has it: what segmentation first asks of every voxel, most of which are
// transparent.
template <typename Table>
double lookUpSigma(const Table& table, double f) {
    const TableSpot at = tableSpot(table, f);
    return interpolate(table.sigma[at.i], table.sigma[at.j], at.w);
}
}  // namespace vr::device
#endif

#endif
