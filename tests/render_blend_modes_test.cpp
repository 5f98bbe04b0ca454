// The blends other than composite on the CPU reference (docs/ALGORITHMS.md section 11): the blocks caster equals
// the primitive one, every blend agrees with a brute force, an axis-aligned MIP is the maximum of each voxel column
// and opposite views of MIP and MinIP are mirror images. The cases are tests/support/blend_cases.*, which the Vulkan
// casters face too.
#include <gtest/gtest.h>

#include "support/blend_cases.h"

namespace vr {
namespace {

TEST(RenderBlendModes, BlocksCasterEqualsPrimitive) {
    test::report("blocks = primitive", test::blocksEqualPrimitive(test::kCpuReference, {}));
}

TEST(RenderBlendModes, BlendsMatchBruteForce) {
    test::report("brute force", test::blendsMatchBruteForce(test::kCpuReference, 0));
}

TEST(RenderBlendModes, AxisMipIsColumnMaximum) {
    test::report("column maximum", test::axisMipIsColumnMaximum(test::kCpuReference, {}));
}

TEST(RenderBlendModes, GreyWindowIsLinearAndOpaque) {
    test::report("grey window", test::greyWindowIsLinear(test::kCpuReference, {}));
}

TEST(RenderBlendModes, OppositeViewsAreMirrorImages) {
    test::report("mirror images", test::oppositeViewsMirror(test::kCpuReference, {}));
}

}  // namespace
}  // namespace vr
