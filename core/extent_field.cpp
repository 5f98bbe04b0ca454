#include "extent_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cstring>

namespace vr {

ExtentField::ExtentField(ExtentCode code, const std::vector<Extents>& boxes) : ExtentField(code, boxes.size()) {
    static_assert(std::endian::native == std::endian::little, "coded extents are stored little-endian");
    const std::size_t n = extentCodeBytes(code);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boxes.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const uint32_t c = encodeExtents(code, boxes[i]);
            std::memcpy(bytes_.data() + i * n, &c, n);
        }
    });
}

}  // namespace vr
