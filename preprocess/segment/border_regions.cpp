#include "preprocess/segment/border_regions.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <limits>

namespace vr {
namespace {

bool touchesOtherRegion(const Regions& regions, int x, int y, int z) {
    const Vec3i& d = regions.dims;
    const uint32_t own = regions.label[linearIndex(d, x, y, z)];
    for (int k = std::max(z - 1, 0); k <= std::min(z + 1, d.z - 1); ++k)
        for (int j = std::max(y - 1, 0); j <= std::min(y + 1, d.y - 1); ++j)
            for (int i = std::max(x - 1, 0); i <= std::min(x + 1, d.x - 1); ++i)
                if (regions.label[linearIndex(d, i, j, k)] != own) return true;
    return false;
}

}  // namespace

void splitBorderVoxels(Regions& regions) {
    const Vec3i d = regions.dims;
    std::vector<uint8_t> border(regions.label.size());
    tbb::parallel_for(tbb::blocked_range<int>(0, d.z), [&](const tbb::blocked_range<int>& zs) {
        for (int z = zs.begin(); z != zs.end(); ++z)
            for (int y = 0; y < d.y; ++y)
                for (int x = 0; x < d.x; ++x) border[linearIndex(d, x, y, z)] = touchesOtherRegion(regions, x, y, z);
    });
    // Relabel in voxel order: a border voxel takes a fresh label, the rest their region's (a region may vanish).
    constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> relabel(regions.count, kUnset);
    uint32_t count = 0;
    for (std::size_t i = 0; i < regions.label.size(); ++i) {
        if (border[i]) {
            regions.label[i] = count++;
        } else {
            uint32_t& to = relabel[regions.label[i]];
            if (to == kUnset) to = count++;
            regions.label[i] = to;
        }
    }
    regions.count = count;
}

}  // namespace vr
