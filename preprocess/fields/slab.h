// Slabs of slices across one axis, copied into local planes and walked in a field's scan order: the EACD steps
// work on whole slices (a face-minimum table per slice), and across x a slice is strided in the volume.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

#include "core/vec3.h"
#include "preprocess/fields/byte_rows.h"

namespace vr {

// Slices [t0, t1) across axis a, copied into local planes: u fastest, then w (the two other axes, u < w), then t,
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

    // local = the slab's voxels of `volume`, and back. Across y or z a local row is a row of the volume; across x
    // each z of the volume holds a (y, x) block of the slab, transposed into (x, y).
    void gather(const uint8_t* volume, uint8_t* local) const {
        for (int pw = 0; pw < nw; ++pw) {
            if (a == 0) {
                transposeBytes(volume + pw * stride[w] + t0, stride[u], local + std::size_t(pw) * nu, pitch, nu, t1 - t0);
                continue;
            }
            for (int t = t0; t < t1; ++t) std::copy_n(volume + t * stride[a] + pw * stride[w], nu, local + at(t, pw));
        }
    }
    void scatter(const uint8_t* local, uint8_t* volume) const {
        for (int pw = 0; pw < nw; ++pw) {
            if (a == 0) {
                transposeBytes(local + std::size_t(pw) * nu, pitch, volume + pw * stride[w] + t0, stride[u], t1 - t0, nu);
                continue;
            }
            for (int t = t0; t < t1; ++t) std::copy_n(local + at(t, pw), nu, volume + t * stride[a] + pw * stride[w]);
        }
    }

private:
    std::size_t at(int t, int pw) const { return std::size_t(t - t0) * pitch + std::size_t(pw) * nu; }
};

// Slices per slab. Across x: 32, so that the gathers read half cache lines of the volume and transpose whole
// 16 x 16 tiles (measured on the teapot: 4 slices, byte by byte, took 1.4x as long). Across y or z, rows of x are
// already contiguous.
inline int slabWidth(int axis) { return axis == 0 ? 32 : 1; }

// Where the neighbour slice of a slice is (see walkSlices): outside the volume, or the last slice of the slab before.
constexpr int kBorder = -1, kSlabBefore = -2;

// Walks every slice across axis a toward -sign, so that the neighbour v + sign e_a of a voxel is done before it:
// gather(slab), then slice(slab, t, tw) per slice in that order (t and tw local; tw may be kBorder or kSlabBefore),
// then finish(slab, t) with t the slice done last (the neighbour of the next slab's first, kept by the caller).
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
            slice(slab, t, tw >= 0 && tw < count ? tw : i == 0 ? kBorder : kSlabBefore);
        }
        finish(slab, sign > 0 ? 0 : count - 1);
    }
}

}  // namespace vr
