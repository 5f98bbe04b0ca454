// The EACD builder's working state (ALGORITHMS.md section 4) and its two extension steps (eacd_extensions.cpp).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/distance_fields.h"
#include "preprocess/fields/axial_runs.h"
#include "preprocess/fields/rect_min.h"

namespace vr {

// A byte per voxel, left uninitialised: each step writes every voxel's slot before any step reads it, and zeroing
// hundreds of megabytes first would cost more than some steps.
class ByteVolume {
public:
    void allocate(std::size_t voxels) { bytes_ = std::make_unique_for_overwrite<uint8_t[]>(voxels); }
    uint8_t* data() { return bytes_.get(); }
    const uint8_t* data() const { return bytes_.get(); }

private:
    std::unique_ptr<uint8_t[]> bytes_;
};

// Working memory of one run direction's walk (eacd_extensions.cpp). Across x, the slab's copies: its runs and, per
// octant of that direction, its inputs (ACD edge k; step 2: widest axis and its extent) and its extension along the
// walked axis (ext); the *Before planes keep the slice done last in the slab before (the neighbour of this slab's
// first). Across y or z the walk reads and writes the volumes themselves. Per octant in any case, each voxel's face
// to query in the current slice (lenU x lenW; lenU = 0 for none, where ext is 0 until the query fills it).
struct WalkScratch {
    RectMin table;
    std::vector<uint8_t> runs;
    std::array<std::vector<uint8_t>, 4> edge, widest, longest, ext, lenU, lenW;
    std::array<std::vector<uint8_t>, 4> edgeBefore, widestBefore, longestBefore, extBefore;
};

// The octants built together. Their extents live in planar byte arrays while being built (ext[o][a][v]: each
// step reads and writes whole slots, so one byte per voxel moves instead of three) and are interleaved at the end.
// widest[o][v] is the axis step 1 extends (the first with the largest extent), longest[o][v] its extent.
struct OctantBatch {
    std::vector<int> octants;
    // Volumes of the octants done, for the next batch: the same memory again, already mapped.
    std::vector<ByteVolume> spare;
    std::array<const std::vector<uint8_t>*, kOctants> acd{};
    std::array<std::array<ByteVolume, 3>, kOctants> ext;
    std::array<ByteVolume, kOctants> widest, longest;
    // Per walk (x, y, z toward +, then toward -): kept for every batch (no fresh pages each time).
    std::array<WalkScratch, 6> scratch;

    // A volume of `voxels` bytes: a spare one (all have the same size) or a new one.
    ByteVolume take(std::size_t voxels) {
        if (spare.empty()) {
            ByteVolume v;
            v.allocate(voxels);
            return v;
        }
        ByteVolume v = std::move(spare.back());
        spare.pop_back();
        return v;
    }

    std::vector<int> withSign(int axis, int sign) const {
        std::vector<int> out;
        for (int o : octants)
            if (octantSign(o, axis) == sign) out.push_back(o);
        return out;
    }
};

// Step 1, along every axis a: ext[o][a] = the extension along a of the ACD cube of every octant of the batch.
void cubeExtensions(AxialRuns& runs, OctantBatch& batch);
// Step 2, along every axis b: ext[o][b] = the extension along b of the box that step 1 extended along widest[o].
void boxExtensions(AxialRuns& runs, OctantBatch& batch);

}  // namespace vr
