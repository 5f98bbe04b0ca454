#include "volrender/vulkan/workgroup_rows.h"

#include <cmath>
#include <numeric>

namespace vr {

int interleavedRowStride(int rows) {
    if (rows <= 2) return 1;
    const double inverseGolden = (std::sqrt(5.0) - 1.0) / 2.0;
    int stride = int(std::lround(rows * inverseGolden));
    while (std::gcd(stride, rows) != 1) ++stride;  // stride < rows: rows - 1 is coprime with rows
    return stride;
}

}  // namespace vr
