// The EACD builder's working state (docs/ALGORITHMS.md section 4) and its two extension steps (eacd_extensions.cpp).
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

// Working memory of one axis' walk (eacd_extensions.cpp). Across x, the slab's copies of the inputs (ACD edge k;
// step 2: widest axis and its extent) and of the extension along x (ext); the *Before planes keep the slice done
// last in the slab before (the neighbour of this slab's first). Across y or z the walk reads and writes the volumes
// themselves. In any case, each voxel's face to query in the current slice (lenU x lenW; lenU = 0 for none, where
// ext is 0 until the query fills it).
struct WalkScratch {
    RectMin table;
    std::vector<uint8_t> edge, widest, longest, ext, lenU, lenW;
    std::vector<uint8_t> edgeBefore, widestBefore, longestBefore, extBefore;
};

// The octant being built, in memory that every octant reuses (no fresh pages after the first). Its extents live in
// planar byte arrays while being built (ext[a][v]: each step reads and writes whole slots, so one byte per voxel
// moves instead of three) and are interleaved at the end. widest[v] is the axis step 1 extends (the first with the
// largest extent), longest[v] its extent.
struct OctantState {
    // Computes the runs that the octants of the mask read and copies those along x into the walks' slabs; sizes
    // the volumes.
    OctantState(AxialRuns& runs, unsigned octants);

    AxialRuns& runs;
    int octant = 0;
    const std::vector<uint8_t>* acd = nullptr;
    std::array<ByteVolume, 3> ext;
    ByteVolume widest, longest;
    // The runs along x toward + and - ([sign < 0]) as the walks across x read them, slice x at x * pitch: copied
    // once for all octants and both steps rather than per walk; only the signs that the octants read.
    std::array<std::vector<uint8_t>, 2> runsAcrossX;
    // Per axis walked, kept for every octant.
    std::array<WalkScratch, 3> scratch;
};

// Step 1, along every axis a: ext[a] = the extension along a of the octant's ACD cube.
void cubeExtensions(OctantState& state);
// Step 2, along every axis b: ext[b] = the extension along b of the box that step 1 extended along widest.
void boxExtensions(OctantState& state);

}  // namespace vr
