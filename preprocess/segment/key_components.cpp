#include "preprocess/segment/key_components.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "core/errors.h"

namespace vr {
namespace {

// Union-find over voxel indices. A set is linked under its smaller root, so every parent is <= its child and the
// root of a set is its first voxel: that is what lets the final pass label in one sweep.
uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];  // path halving
        i = parent[i];
    }
    return i;
}

void unite(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
    a = findRoot(parent, a);
    b = findRoot(parent, b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
}

template <typename Key>
void keySlice(const RegionKeyer& keyer, const Vec3i& dims, int z, std::vector<Key>& keys) {
    keyer.keys(linearIndex(dims, 0, 0, z), keys.size(), keys.data());
}

// Unites the voxels of slice z with their -x and -y neighbours of equal key. A voxel is still alone when its turn
// comes (voxels are joined in index order), so joining its left neighbour is one store; its upper neighbour is
// already in the same set when the left and upper-left voxels are equal to both.
template <typename Key>
void uniteInSlice(std::vector<uint32_t>& parent, const Vec3i& dims, int z, const std::vector<Key>& keys) {
    const uint32_t base = uint32_t(linearIndex(dims, 0, 0, z));
    const uint32_t nx = uint32_t(dims.x);
    for (int y = 0; y < dims.y; ++y)
        for (uint32_t x = 0; x < nx; ++x) {
            const uint32_t j = uint32_t(y) * nx + x;
            const bool left = x > 0 && keys[j] == keys[j - 1];
            if (left) parent[base + j] = parent[base + j - 1];
            if (y > 0 && keys[j] == keys[j - nx] && !(left && keys[j - nx] == keys[j - nx - 1]))
                unite(parent, base + j, base + j - nx);
        }
}

// Unites the voxels of slice z with their -z neighbours (slice z-1, keys `below`) of equal key, skipping those
// already joined through their -x neighbour (both slices' in-slice unions are done).
template <typename Key>
void uniteWithBelow(std::vector<uint32_t>& parent, const Vec3i& dims, int z, const std::vector<Key>& keys,
                    const std::vector<Key>& below) {
    const uint32_t base = uint32_t(linearIndex(dims, 0, 0, z)), slice = uint32_t(keys.size());
    const uint32_t nx = uint32_t(dims.x);
    for (uint32_t j = 0; j < slice; ++j)
        if (keys[j] == below[j] &&
            !(j % nx > 0 && keys[j] == keys[j - 1] && below[j] == below[j - 1]))
            unite(parent, base + j, base + j - slice);
}

// Links every voxel to a smaller one of its component (parent[i] <= i), with Key = RegionKey or PackedKey.
template <typename Key>
void uniteComponents(std::vector<uint32_t>& parent, const Vec3i& dims, const RegionKeyer& keyer) {
    const std::size_t n = parent.size();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) parent[i] = uint32_t(i);
    });

    // Slabs of slices are labelled in parallel (a slab's unions stay inside it), then the seams are joined.
    const std::size_t slice = std::size_t(dims.x) * std::size_t(dims.y);
    const int slabs = std::min(dims.z, 4 * tbb::info::default_concurrency());
    const auto slabStart = [&](int s) { return int(std::int64_t(s) * dims.z / slabs); };
    tbb::parallel_for(0, slabs, [&](int s) {
        std::vector<Key> keys(slice), below(slice);
        for (int z = slabStart(s); z < slabStart(s + 1); ++z) {
            keySlice(keyer, dims, z, keys);
            uniteInSlice(parent, dims, z, keys);
            if (z > slabStart(s)) uniteWithBelow(parent, dims, z, keys, below);
            std::swap(keys, below);
        }
    });
    std::vector<Key> keys(slice), below(slice);
    for (int s = 1; s < slabs; ++s) {
        const int z = slabStart(s);
        keySlice(keyer, dims, z - 1, below);
        keySlice(keyer, dims, z, keys);
        uniteWithBelow(parent, dims, z, keys, below);
    }
}

}  // namespace

void labelKeyComponents(const Vec3i& dims, const RegionKeyer& keyer, Regions& regions) {
    const std::size_t n = voxelCount(dims);
    if (n >= std::numeric_limits<uint32_t>::max())
        throw InputError("segmentation: " + std::to_string(n) + " voxels; at most 2^32 - 1 are supported");
    regions.dims = dims;
    std::vector<uint32_t>& parent = regions.label;  // the parents become the labels in the last pass
    parent.resize(n);
    if (keyer.packs()) {
        uniteComponents<PackedKey>(parent, dims, keyer);
    } else {
        uniteComponents<RegionKey>(parent, dims, keyer);
    }

    // parent[i] <= i: a root takes the next label, any other voxel its (already relabelled) parent's label.
    uint32_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const uint32_t p = parent[i];
        parent[i] = p == i ? count++ : parent[p];
    }
    regions.count = count;
}

}  // namespace vr
