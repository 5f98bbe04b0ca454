#include "preprocess/segment/normal_classes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vr {

NormalClasses::NormalClasses(const RegionKeyer& keyer, std::size_t voxels) : keyer_(keyer) {
    if (!used() || !keyer.binsNormals()) return;  // bit-equal normals are compared where they are stored
    binned_.resize(voxels);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxels), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const RegionKey key = keyer.normalKey(i);
            binned_[i] = key.opacity == 0 ? 0 : 1 + key.normal[0];
        }
    });
}

}  // namespace vr
