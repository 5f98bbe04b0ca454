#include "preprocess/segment/normal_classes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>

namespace vr {

NormalClasses::NormalClasses(const RegionKeyer& keyer, std::size_t voxels, const Progress& progress)
    : used_(keyer.usesNormals()) {
    if (!used_) return;
    const bool binned = keyer.binsNormals(), narrow = binned && keyer.normalCells() < 65535;
    if (narrow) narrow_.resize(voxels);
    else if (binned) binned_.resize(voxels);
    else exact_.resize(voxels);
    constexpr uint32_t kNaN = 0x7fc00000;  // never a unit or flat normal's component
    // In runs of 2^20 voxels, each reported as it is keyed.
    std::atomic<std::size_t> keyed{0};
    const auto keyRun = [&](const tbb::blocked_range<std::size_t>& r) {
        std::array<RegionKey, 1024> keys;  // keyed a piece at a time, rows' normals together
        for (std::size_t at = r.begin(); at < r.end(); at += keys.size()) {
            const std::size_t count = std::min(keys.size(), r.end() - at);
            keyer.normalKeys(at, count, keys.data());
            for (std::size_t k = 0; k < count; ++k) {
                const RegionKey& key = keys[k];
                const std::size_t i = at + k;
                const bool transparent = key.opacity == 0;
                const uint32_t cell = transparent ? 0 : 1 + key.normal[0];
                if (narrow) narrow_[i] = uint16_t(cell);
                else if (binned) binned_[i] = cell;
                else exact_[i] = transparent ? std::array<uint32_t, 3>{kNaN, kNaN, kNaN} : key.normal;
            }
        }
        if (progress) progress(double(keyed += r.size()) / double(voxels));
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxels, std::size_t(1) << 20), keyRun, tbb::simple_partitioner());
}

}  // namespace vr
