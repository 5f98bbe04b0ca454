// Slabs of slices across one axis, walked in a field's scan order: the EACD steps work on whole slices (a
// face-minimum table per slice). Across y or z a slice's rows are rows of the volume, so a walk reads and writes
// them in place; across x a slice is strided in the volume, so slabs of slices are copied into local planes.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "core/vec3.h"
#include "preprocess/fields/byte_rows.h"

namespace vr {

// One slice of an array as rows of nu bytes along u: row pw starts at base + pw * stride.
template <typename Byte>
struct RowsOf {
    Byte* base = nullptr;
    std::size_t stride = 0;
    Byte* row(int pw) const { return base + std::size_t(pw) * stride; }
};
using Rows = RowsOf<const uint8_t>;
using MutableRows = RowsOf<uint8_t>;

// Slices [t0, t1) across axis a; when copied, into local planes: u fastest, then w (the two other axes, u < w), then t,
// `pitch` bytes apart: an odd number of cache lines, so that the 16 planes a transposed tile writes (or reads) do not
// all fall in the same cache set, as they would 64 KiB apart.
struct Slab {
    int a, u, w, nu, nw, t0, t1;
    std::size_t plane, pitch;
    std::array<std::size_t, 3> stride;

    Slab(const Vec3i& n, int axis, int first, int last)
        : a(axis), u(axis == 0 ? 1 : 0), w(axis == 2 ? 1 : 2), nu(n[u]), nw(n[w]), t0(first), t1(last),
          plane(std::size_t(nu) * nw), pitch((plane + 63) / 128 * 128 + 64),
          stride{1, std::size_t(n.x), std::size_t(n.x) * n.y} {}

    std::size_t size() const { return pitch * std::size_t(t1 - t0); }
    // Across y or z the walk works on the volume's rows (inVolume); across x on copies (gather, scatter).
    bool inPlace() const { return a != 0; }
    // Slice t0 + t of a volume (t may lie outside the slab).
    template <typename Byte>
    RowsOf<Byte> inVolume(Byte* volume, int t) const {
        return {volume + std::size_t(t0 + t) * stride[a], stride[w]};
    }

    // copy = the slab's voxels of `volume`, and back: each z of the volume holds a (y, x) block of the slab,
    // transposed into (x, y). Across x only.
    void gather(const uint8_t* volume, uint8_t* copy) const {
        for (int pw = 0; pw < nw; ++pw)
            transposeBytes(volume + pw * stride[w] + t0, stride[u], copy + std::size_t(pw) * nu, pitch, nu, t1 - t0);
    }
    void scatter(const uint8_t* copy, uint8_t* volume) const {
        for (int pw = 0; pw < nw; ++pw)
            transposeBytes(copy + std::size_t(pw) * nu, pitch, volume + pw * stride[w] + t0, stride[u], t1 - t0, nu);
    }
};

// Slices per slab. Across x: 64, so that the gathers read a cache line's width of each row and transpose whole
// 16 x 16 tiles (EACD CPU time against 32 slices: 0.91x at 256^3 on the teapot, 0.90x at 512^3; 128 slices took
// longer again; 4 slices, byte by byte, 1.4x). Across y or z, in place.
inline int slabWidth(int axis) { return axis == 0 ? 64 : 1; }

// The neighbour slice of a border slice (see walkSlices): outside the volume.
constexpr int kBorder = std::numeric_limits<int>::min();

// Walks every slice across axis a toward -sign, so that the neighbour v + sign e_a of a voxel is done before it:
// gather(slab), then slice(slab, t, tw) per slice in that order (t and tw = t + sign local; tw is -1 or the slab's
// width for the neighbour in the slab before, kBorder outside the volume), then finish(slab, t) with t the slice
// done last (the neighbour of the next slab's first, kept by the caller when the slab is a copy).
template <typename Gather, typename Slice, typename Finish>
void walkSlices(const Vec3i& n, int a, int sign, Gather gather, Slice slice, Finish finish) {
    const int width = slabWidth(a), slabs = (n[a] + width - 1) / width;
    for (int i = 0; i < slabs; ++i) {
        const int s = sign > 0 ? slabs - 1 - i : i;
        const Slab slab(n, a, s * width, std::min(n[a], (s + 1) * width));
        const int count = slab.t1 - slab.t0;
        gather(slab);
        for (int k = 0; k < count; ++k) {
            const int t = sign > 0 ? count - 1 - k : k, tw = t + sign;
            slice(slab, t, (tw >= 0 && tw < count) || i > 0 ? tw : kBorder);
        }
        finish(slab, sign > 0 ? 0 : count - 1);
    }
}

}  // namespace vr
