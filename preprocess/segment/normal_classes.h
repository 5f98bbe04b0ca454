// Voxels alike in their normals as the region key has them (region_key.h), for post-classified regions.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "preprocess/segment/region_key.h"

namespace vr {

class NormalClasses {
public:
    // Each voxel's normal class, keyed once: the normals are taken from the scalars' gradient on demand, too dear
    // to take again for every neighbour compared. `progress` hears the share of voxels keyed.
    NormalClasses(const RegionKeyer& keyer, std::size_t voxels, const Progress& progress = {});
    // Whether normals constrain the regions: shading uses them and the volume has them.
    bool used() const { return used_; }
    // An equivalence: normals unused, or both voxels transparent, or both flat, or both in one cube-map cell
    // (bit for bit at T_a = 0).
    bool alike(std::size_t a, std::size_t b) const {
        if (!used_) return true;
        if (!narrow_.empty()) return narrow_[a] == narrow_[b];
        return binned_.empty() ? exact_[a] == exact_[b] : binned_[a] == binned_[b];
    }

private:
    bool used_;
    // Where normals are binned: 0 transparent, else 1 + the key's normal cell; in 16 bits where the cells allow
    // (T_a of 1.6 degrees or more: 6 K^2 < 65535).
    std::vector<uint16_t> narrow_;
    std::vector<uint32_t> binned_;
    std::vector<std::array<uint32_t, 3>> exact_;  // elsewhere the normal's bits; a NaN's for transparent voxels
};

}  // namespace vr
