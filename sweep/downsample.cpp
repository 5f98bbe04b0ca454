#include "sweep/downsample.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace vr {

Volume downsample(const Volume& in, int f) {
    if (f < 1) throw InputError("downsampling factor " + std::to_string(f) + ": must be at least 1");
    if (f == 1) return in;
    const Vec3i n = in.grid.dims;
    const Vec3i m{(n.x + f - 1) / f, (n.y + f - 1) / f, (n.z + f - 1) / f};
    Volume out;
    out.grid = {m, in.grid.spacing * double(f), in.grid.origin};
    out.sourceType = in.sourceType;
    out.source = in.source;
    out.values.resize(out.grid.voxels());
    const bool integer = in.sourceType != ScalarType::Float32;
    tbb::parallel_for(0, m.z, [&](int z) {
        for (int y = 0; y < m.y; ++y)
            for (int x = 0; x < m.x; ++x) {
                double sum = 0;
                int count = 0;
                for (int k = z * f; k < std::min(n.z, (z + 1) * f); ++k)
                    for (int j = y * f; j < std::min(n.y, (y + 1) * f); ++j)
                        for (int i = x * f; i < std::min(n.x, (x + 1) * f); ++i, ++count) sum += in.at(i, j, k);
                const double mean = sum / count;
                out.values[linearIndex(m, x, y, z)] = float(integer ? std::round(mean) : mean);
            }
    });
    return out;
}

}  // namespace vr
