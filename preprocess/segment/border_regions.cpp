#include "preprocess/segment/border_regions.h"

#include <limits>

#include "preprocess/segment/mixed_neighbourhoods.h"

namespace vr {

void splitBorderVoxels(Regions& regions) {
    const std::vector<uint32_t>& l = regions.label;
    const std::vector<uint8_t> border =
        mixedNeighbourhoods(regions.dims, [&](std::size_t a, std::size_t b) { return l[a] == l[b]; });
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
