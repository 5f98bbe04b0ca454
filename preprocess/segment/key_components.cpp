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

void keySlice(const RegionKeyer& keyer, const Vec3i& dims, int z, std::vector<RegionKey>& keys) {
    const std::size_t base = linearIndex(dims, 0, 0, z);
    for (std::size_t j = 0; j < keys.size(); ++j) keys[j] = keyer(base + j);
}

// Unites the voxels of slice z with their -x and -y neighbours of equal key.
void uniteInSlice(std::vector<uint32_t>& parent, const Vec3i& dims, int z, const std::vector<RegionKey>& keys) {
    const uint32_t base = uint32_t(linearIndex(dims, 0, 0, z));
    for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) {
            const uint32_t j = uint32_t(y * dims.x + x);
            if (x > 0 && keys[j] == keys[j - 1]) unite(parent, base + j, base + j - 1);
            if (y > 0 && keys[j] == keys[j - dims.x]) unite(parent, base + j, base + j - dims.x);
        }
}

// Unites the voxels of slice z with their -z neighbours (slice z-1, keys `below`) of equal key.
void uniteWithBelow(std::vector<uint32_t>& parent, const Vec3i& dims, int z, const std::vector<RegionKey>& keys,
                    const std::vector<RegionKey>& below) {
    const uint32_t base = uint32_t(linearIndex(dims, 0, 0, z)), slice = uint32_t(keys.size());
    for (uint32_t j = 0; j < slice; ++j)
        if (keys[j] == below[j]) unite(parent, base + j, base + j - slice);
}

}  // namespace

Regions labelKeyComponents(const Vec3i& dims, const RegionKeyer& keyer) {
    const std::size_t n = voxelCount(dims);
    if (n >= std::numeric_limits<uint32_t>::max())
        throw InputError("segmentation: " + std::to_string(n) + " voxels; at most 2^32 - 1 are supported");
    Regions regions;
    regions.dims = dims;
    std::vector<uint32_t>& parent = regions.label;  // the parents become the labels in the last pass
    parent.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) parent[i] = uint32_t(i);
    });

    // Slabs of slices are labelled in parallel (a slab's unions stay inside it), then the seams are joined.
    const std::size_t slice = std::size_t(dims.x) * std::size_t(dims.y);
    const int slabs = std::min(dims.z, 4 * tbb::info::default_concurrency());
    const auto slabStart = [&](int s) { return int(std::int64_t(s) * dims.z / slabs); };
    tbb::parallel_for(0, slabs, [&](int s) {
        std::vector<RegionKey> keys(slice), below(slice);
        for (int z = slabStart(s); z < slabStart(s + 1); ++z) {
            keySlice(keyer, dims, z, keys);
            uniteInSlice(parent, dims, z, keys);
            if (z > slabStart(s)) uniteWithBelow(parent, dims, z, keys, below);
            std::swap(keys, below);
        }
    });
    std::vector<RegionKey> keys(slice), below(slice);
    for (int s = 1; s < slabs; ++s) {
        const int z = slabStart(s);
        keySlice(keyer, dims, z - 1, below);
        keySlice(keyer, dims, z, keys);
        uniteWithBelow(parent, dims, z, keys, below);
    }

    // parent[i] <= i: a root takes the next label, any other voxel its (already relabelled) parent's label.
    uint32_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const uint32_t p = parent[i];
        parent[i] = p == i ? count++ : parent[p];
    }
    regions.count = count;
    return regions;
}

}  // namespace vr
