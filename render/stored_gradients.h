// Stored gradients (docs/ALGORITHMS.md section 2): each voxel's central-difference gradient (core/gradient.h) in the
// 32-bit code of shaders/gradient_code.h, which the casters read in place of the scalars' differences. The CPU
// reference decodes the same codes, so both shade by the same gradients.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "core/scalar_classification.h"
#include "core/volume.h"
#include "shaders/gradient_code.h"

namespace vr {

// Packs the gradients of one volume: per exponent, the longest component it holds (rounded) and the inverse of its
// unit, so that packing a voxel calls no maths library.
class GradientPacker {
public:
    // The base exponent: the least whose exponent 31 holds a component `largest` long in 255 units (0 for none).
    static int baseFor(double largest);
    // A volume's packer: its largest possible gradient is the transfer table's scalar span over the smallest
    // spacing (a one-sided difference across the whole range).
    GradientPacker(const Volume& scalars, const TransferTable& table);
    explicit GradientPacker(int base);

    int base() const { return base_; }
    // The code of g: the least exponent that holds its longest component, each component rounded to the nearest
    // unit. A component finer than the last exponent's unit rounds to 0; g = 0 (or not finite) is code 0.
    std::uint32_t pack(const Vec3d& g) const;
    // The codes of `count` voxels along x from linear index `first`, written to `to`.
    void packRow(const Volume& scalars, std::size_t first, int count, std::uint32_t* to) const;
    // Voxel v's gradient as its code holds it.
    Vec3d stored(const Volume& scalars, const Vec3i& v) const;

private:
    static constexpr int kExponents = device::kGradientExponentMax + 1;
    int base_;
    std::array<double, kExponents> longest_;  // the longest component exponent e holds: 255.5 units
    std::array<double, kExponents> inverseUnit_;
};

}  // namespace vr
