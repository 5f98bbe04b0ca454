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

// kFieldHier: the hierarchical EACD (BlockEACD), built from the scalars and their classification, not the regions.
enum FieldKind : unsigned { kFieldPC = 1, kFieldACD = 2, kFieldEACD = 4, kFieldHier = 8 };
// The fields built over the voxels' regions.
constexpr unsigned kRegionFields = kFieldPC | kFieldACD | kFieldEACD;

// The hierarchical EACD's coarse level (docs/ALGORITHMS.md section 10): the EACD over blocks of 2^blockShift voxels
// per axis, in block units. Per octant one log16 code per block (x fastest), the block's box in blocks, with
// kHomogeneousBlockBit set where the block is homogeneous; a mixed block holds 0.
constexpr uint16_t kHomogeneousBlockBit = 0x8000;
// The blocks' edge that volrender builds: 4 voxels (docs/ALGORITHMS.md section 10 has the measurements).
constexpr int kHierBlockShift = 2;

struct BlockEACD {
    int blockShift = kHierBlockShift;
    Vec3i blocks{0, 0, 0};  // per axis: the voxels / 2^blockShift, rounded up
    std::array<ExtentField, kOctants> octant;

    // Bit o set where octant o is held (those of a render's views).
    unsigned octants() const {
        unsigned m = 0;
        for (int o = 0; o < kOctants; ++o) m |= octant[o].empty() ? 0u : 1u << o;
        return m;
    }
    bool empty() const { return octants() == 0; }
    std::size_t bytes() const {
        std::size_t b = 0;
        for (const ExtentField& f : octant) b += f.bytes();
        return b;
    }
    // The code of the block that holds voxel v, in a held octant.
    uint16_t code(int oct, const Vec3i& v) const {
        const std::size_t x = std::size_t(v.x >> blockShift), y = std::size_t(v.y >> blockShift),
                          z = std::size_t(v.z >> blockShift);
        const std::size_t i = (z * std::size_t(blocks.y) + y) * std::size_t(blocks.x) + x;
        const uint8_t* b = octant[oct].data() + 2 * i;
        return uint16_t(b[0] | b[1] << 8);
    }
};

struct DistanceFields {
    Vec3i dims{0, 0, 0};
    // PC: Chebyshev radius r >= 0 of the cube centred on v that stays in v's region and inside the volume.
    std::vector<uint8_t> pc;
    // ACD: per octant, the edge k >= 1 of the cube {v + s*e : e in [0,k)^3} in v's region and inside the volume.
    std::array<std::vector<uint8_t>, kOctants> acd;
    // EACD: per octant, extents (ex, ey, ez) >= 1 of the box {v + s*e : 0 <= e_a < ext_a}, in one code for all
    // octants (extent_field.h); exact extents are >= acd, coded ones (rounded down) may be smaller on some axis.
    std::array<ExtentField, kOctants> eacd;
    BlockEACD hier;

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
