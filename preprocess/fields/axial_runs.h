// Axial run lengths, the building block of ACD and EACD (docs/ALGORITHMS.md section 4).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/distance_fields.h"
#include "core/regions.h"

namespace vr {

// run[u] = number of voxels of u's region met from u stepping by `sign` along `axis`, u included, stopping at the
// volume border. Cap: runs above kDistanceCap (255) are stored as 255 (a shorter run is still homogeneous).
std::vector<uint8_t> axialRuns(const Regions& regions, int axis, int sign);

// The six run fields of one Regions, each computed once and shared by the ACD and EACD builders.
class AxialRuns {
public:
    explicit AxialRuns(const Regions& regions);  // throws std::invalid_argument when labels and dims disagree
    const Regions& regions() const { return regions_; }
    const Vec3i& dims() const { return regions_.dims; }
    // Computes the field on first use: not for concurrent first uses (call computeAll() before going parallel).
    const std::vector<uint8_t>& get(int axis, int sign);
    // In parallel, the fields that the octants of the mask read (each octant one sign per axis): all six for all
    // octants, three for one (an orthographic view's).
    void computeAll(unsigned octants = kAllOctants);
    // Whether some octant of the mask reads the runs along `axis` toward `sign`.
    static bool read(unsigned octants, int axis, int sign) {
        for (int o = 0; o < kOctants; ++o)
            if ((octants >> o & 1u) && octantSign(o, axis) == sign) return true;
        return false;
    }

private:
    const Regions& regions_;
    std::array<std::vector<uint8_t>, 6> runs_;
};

}  // namespace vr
