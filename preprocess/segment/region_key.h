// The quantisation behind the regions (docs/ALGORITHMS.md section 3): voxels with equal keys are similar, with a bound
// that holds for every pair of them, not only for neighbours.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

#include "core/regions.h"
#include "preprocess/segment/classified_voxels.h"

namespace vr {

// Two voxels with equal keys are both transparent (sigma = 0: colour and normal contribute nothing and are
// ignored), or both opaque with
//  - opacities per reference step in the same bin [k T_o, (k+1) T_o), so they differ by less than T_o,
//    and likewise each colour channel;
//  - normals both flat, or both in one cube-map cell of angular diameter <= T_a (normals ignored when
//    params.useNormals is false or the volume has none).
// A threshold of 0 (or one so small that its bins would not fit 32 bits) compares the stored floats bit for bit.
// With a label map, two voxels with equal keys also have one label, transparent or not: a leap never crosses a
// label's boundary.
struct RegionKey {
    uint32_t opacity = 0;  // 0 = transparent
    std::array<uint32_t, 3> colour{};
    std::array<uint32_t, 3> normal{};
    uint32_t label = 0;
    bool operator==(const RegionKey& o) const {  // field by field: cheaper than the defaulted memcmp here
        return opacity == o.opacity && label == o.label && colour[0] == o.colour[0] && colour[1] == o.colour[1] &&
               colour[2] == o.colour[2] && normal[0] == o.normal[0] && normal[1] == o.normal[1] &&
               normal[2] == o.normal[2];
    }
};

// Cells per cube-face edge for normals within `angleDeg` of each other; 0 = one cell for every direction
// (angleDeg >= 180). The inverse gnomonic projection shrinks lengths, so a cell of side 2/K (diagonal 2 sqrt2 / K)
// spans at most 2 sqrt2 / K radians: K = ceil(2 sqrt2 / T_a).
int cubeMapCellsPerEdge(double angleDeg);
// Cell of a non-zero direction on a cube map with `cellsPerEdge` cells per face edge, in [0, 6 K^2).
uint32_t cubeMapCell(const std::array<float, 3>& direction, int cellsPerEdge);

// A RegionKey in 64 bits where the thresholds bin every field (RegionKeyer::packs): equal packed keys <=> equal keys.
using PackedKey = uint64_t;

// Throws InputError naming the threshold where T_o or T_a is negative or NaN.
void checkThresholds(const SegmentationParams& params);

class RegionKeyer {
public:
    // Keys of `voxels` (copied: a view whose volume or table must outlive the keyer). Throws InputError for a
    // negative or NaN threshold.
    RegionKeyer(const ClassifiedVoxels& voxels, const SegmentationParams& params);
    RegionKey operator()(std::size_t voxel) const;
    // The key's normal part alone: a default key where the voxel is transparent, else opacity 1 and the normal
    // binned (or its bits) as operator() has it; default normals where normals are ignored.
    RegionKey normalKey(std::size_t voxel) const;
    // normalKey() of voxels first .. first + count - 1 into out, their normals taken a row at a time
    // (ClassifiedVoxels::normals) where a piece of a row holds one that is not transparent.
    void normalKeys(std::size_t first, std::size_t count, RegionKey* out) const;
    bool usesNormals() const { return useNormals_; }
    // Whether normals are binned into cube-map cells (T_a > 0): the normal key is then normal[0] alone, below
    // normalCells().
    bool binsNormals() const { return !exactNormals_; }
    uint32_t normalCells() const {
        const uint32_t k = uint32_t(std::max(cellsPerEdge_, 1));
        return 6 * k * k;
    }
    // The keys of voxels first .. first + count - 1 into out: operator() for each, but the bins of a (sigma, colour)
    // seen recently in the run are looked up, not recomputed (a volume classified by a TF has few distinct ones).
    void keys(std::size_t first, std::size_t count, RegionKey* out) const;
    // Whether every key packs into a PackedKey without loss: opacity and colour binned (T_o > 0) and normals
    // ignored or binned into cells (T_a > 0), with bins few enough to fit 64 bits (compared bit for bit, the
    // stored floats take 32 bits each), and no label map.
    bool packs() const { return packs_; }
    // keys() packed; only where packs().
    void keys(std::size_t first, std::size_t count, PackedKey* out) const;

private:
    template <typename Key>
    void keysInto(std::size_t first, std::size_t count, Key* out) const;
    PackedKey pack(const RegionKey& key) const;
    uint32_t bin(double value, double width, float exact) const;
    void opacityAndColour(const VoxelOptics& optics, RegionKey& key) const;
    void normal(std::size_t voxel, RegionKey& key) const;
    void normal(const std::array<float, 3>& n, RegionKey& key) const;

    const ClassifiedVoxels voxels_;
    double opacityWidth_ = 0;  // bin width of opacity and colour; 0 = exact
    bool useNormals_ = false;
    bool exactNormals_ = true;
    int cellsPerEdge_ = 0;
    bool packs_ = false;
    int binBits_ = 0;  // bits of each packed opacity and colour bin
};

}  // namespace vr
