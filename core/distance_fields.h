// Distance fields over the regions (docs/ALGORITHMS.md section 4); distances in voxels.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "extent_field.h"
#include "vec3.h"

namespace vr {

// Every distance is stored in one byte and capped here (a capped value is still conservative: the box shrinks).
constexpr int kDistanceCap = 255;
constexpr int kOctants = 8;
constexpr unsigned kAllOctants = (1u << kOctants) - 1;  // a mask of octants (bit o: octant o) holding them all

// Octant of a direction: bit a set when component a is negative (a zero component counts as positive).
inline int octantOf(double dx, double dy, double dz) { return (dx < 0) | ((dy < 0) << 1) | ((dz < 0) << 2); }
// Step sign of axis a in octant oct.
constexpr int octantSign(int oct, int axis) { return (oct >> axis) & 1 ? -1 : +1; }

enum FieldKind : unsigned { kFieldPC = 1, kFieldACD = 2, kFieldEACD = 4 };

struct DistanceFields {
    Vec3i dims{0, 0, 0};
    // PC: Chebyshev radius r >= 0 of the cube centred on v that stays in v's region and inside the volume.
    std::vector<uint8_t> pc;
    // ACD: per octant, the edge k >= 1 of the cube {v + s*e : e in [0,k)^3} in v's region and inside the volume.
    std::array<std::vector<uint8_t>, kOctants> acd;
    // EACD: per octant, extents (ex, ey, ez) >= 1 of the box {v + s*e : 0 <= e_a < ext_a}, in one code for all
    // octants (extent_field.h); exact extents are >= acd, coded ones (rounded down) may be smaller on some axis.
    std::array<ExtentField, kOctants> eacd;

    // Bit o set where octant o's ACD (EACD) is held: all eight as volprep builds them, or only those the views of
    // a render need (volrender's one-command path).
    unsigned acdOctants() const {
        unsigned m = 0;
        for (int o = 0; o < kOctants; ++o) m |= acd[o].empty() ? 0u : 1u << o;
        return m;
    }
    unsigned eacdOctants() const {
        unsigned m = 0;
        for (int o = 0; o < kOctants; ++o) m |= eacd[o].empty() ? 0u : 1u << o;
        return m;
    }
    bool hasPC() const { return !pc.empty(); }
    bool hasACD() const { return acdOctants() != 0; }
    bool hasEACD() const { return eacdOctants() != 0; }
    ExtentCode eacdCode() const {
        for (const ExtentField& e : eacd)
            if (!e.empty()) return e.code();
        return eacd[0].code();
    }
};

}  // namespace vr
