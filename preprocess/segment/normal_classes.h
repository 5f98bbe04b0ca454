// Voxels alike in their normals as the region key has them (region_key.h), for post-classified regions.
#pragma once
#include <cstdint>
#include <vector>

#include "preprocess/segment/region_key.h"

namespace vr {

class NormalClasses {
public:
    NormalClasses(const RegionKeyer& keyer, std::size_t voxels);
    // Whether normals constrain the regions: shading uses them and the volume has them.
    bool used() const { return keyer_.usesNormals(); }
    // An equivalence: normals unused, or both voxels transparent, or both flat, or both in one cube-map cell
    // (bit for bit at T_a = 0).
    bool alike(std::size_t a, std::size_t b) const {
        if (!used()) return true;
        return binned_.empty() ? keyer_.normalKey(a) == keyer_.normalKey(b) : binned_[a] == binned_[b];
    }

private:
    const RegionKeyer& keyer_;
    std::vector<uint32_t> binned_;  // where normals are binned: 0 transparent, else 1 + the key's normal cell
};

}  // namespace vr
