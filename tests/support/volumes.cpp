#include "support/volumes.h"

#include <algorithm>

namespace vr::test {

Volume volumeOf(Vec3i dims, Vec3d spacing, ScalarType type, const std::function<double(int, int, int)>& f) {
    Volume v;
    v.grid.dims = dims;
    v.grid.spacing = spacing;
    v.sourceType = type;
    v.values.resize(v.grid.voxels());
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) v.values[linearIndex(dims, x, y, z)] = float(f(x, y, z));
    return v;
}

Volume centralBlock(const Volume& v, int edge) {
    const Vec3i& d = v.grid.dims;
    const Vec3i size{std::min(d.x, edge), std::min(d.y, edge), std::min(d.z, edge)};
    const Vec3i lo = Vec3i{d.x - size.x, d.y - size.y, d.z - size.z} / 2;
    Volume block = v;
    block.grid.dims = size;
    block.grid.origin = v.grid.origin + Vec3d(lo) * v.grid.spacing;
    block.values.resize(voxelCount(size));
    for (int z = 0; z < size.z; ++z)
        for (int y = 0; y < size.y; ++y)
            for (int x = 0; x < size.x; ++x)
                block.values[linearIndex(size, x, y, z)] = v.at(lo.x + x, lo.y + y, lo.z + z);
    return block;
}

Volume everyOtherVoxel(const Volume& v) {
    Volume half = v;
    half.grid.dims = v.grid.dims / 2;
    half.grid.spacing = v.grid.spacing * 2.0;
    half.values.resize(voxelCount(half.grid.dims));
    for (int z = 0; z < half.grid.dims.z; ++z)
        for (int y = 0; y < half.grid.dims.y; ++y)
            for (int x = 0; x < half.grid.dims.x; ++x)
                half.values[linearIndex(half.grid.dims, x, y, z)] = v.at(2 * x, 2 * y, 2 * z);
    return half;
}

}  // namespace vr::test
