#include "preprocess/load/load_labels.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"

namespace vr {
namespace {

std::string gridText(const GridGeometry& g) {
    std::ostringstream s;
    s << g.dims.x << "x" << g.dims.y << "x" << g.dims.z << " voxels, spacing " << g.spacing.x << "," << g.spacing.y
      << "," << g.spacing.z;
    return s.str();
}

// The same grid as a writer rounds it: equal dims and spacings within a millionth of each other. Origins are not
// compared: a raw volume states none, and each format's reader places the first voxel as its format says.
bool sameGrid(const GridGeometry& a, const GridGeometry& b) {
    if (a.dims != b.dims) return false;
    for (int i = 0; i < 3; ++i)
        if (std::abs(a.spacing[i] - b.spacing[i]) > 1e-6 * std::max(a.spacing[i], b.spacing[i])) return false;
    return true;
}

}  // namespace

LabelMap loadLabelMap(const std::filesystem::path& path, const GridGeometry& grid, const char* flag) {
    const std::string where = std::string(flag) + " " + path.string();
    Volume v;
    try {
        // A headerless raw map has no spacing of its own: it takes the volume's (its dims and type from its name).
        RawOptions raw;
        if (isRawFileName(path)) raw.spacing = grid.spacing;
        v = loadVolume(path, raw);
    } catch (const InputError& e) {
        throw InputError(std::string(flag) + ": " + e.what());
    }
    if (!sameGrid(v.grid, grid))
        throw InputError(where + ": the label map's grid (" + gridText(v.grid) +
                         ") is not the volume's (" + gridText(grid) + "): labels must lie on the volume's voxels");
    const std::size_t n = v.values.size();
    // The first voxel whose value is no label, so that the message names the same one on every run.
    const std::size_t bad = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n), n,
        [&](const tbb::blocked_range<std::size_t>& r, std::size_t found) {
            for (std::size_t i = r.begin(); i < r.end() && i < found; ++i) {
                const float f = v.values[i];
                if (!(f >= 0 && f <= float(kMaxLabel) && f == std::floor(f))) return i;
            }
            return found;
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
    if (bad < n) {
        std::ostringstream s;
        s << where << ": voxel " << bad << " holds " << v.values[bad] << ", not a label (labels are integers 0 to "
          << kMaxLabel << "; is this an intensity volume?)";
        throw InputError(s.str());
    }
    LabelMap map;
    map.label.resize(n);
    uint16_t largest = 0;
    for (std::size_t i = 0; i < n; ++i) {
        map.label[i] = uint16_t(v.values[i]);
        largest = std::max(largest, map.label[i]);
    }
    map.type = largest < 256 ? ScalarType::UInt8 : ScalarType::UInt16;
    map.source = path.string();
    return map;
}

}  // namespace vr
