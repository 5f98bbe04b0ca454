// Extreme geometry on the CPU reference (docs/ALGORITHMS.md section 6): rays along axes and diagonals, through voxel
// edges and corners, grazing and missing, eyes inside the volume and on voxel corners; volumes of 1 voxel, lines,
// primes, spacing ratios of 1:100; constant, checkerboard, noise, transparent and opaque content. PC, ACD and EACD
// must give primitive's image with finite values, fetch counts as the fields predict, and the iteration cap must
// fail a render rather than hang it.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/render_cases.h"

namespace vr {
namespace {

using test::kCpuReference;

TEST(RenderExtremeGeometry, CastersEqualPrimitiveOnEveryShapeContentAndView) {
    test::report("extreme geometry", test::extremeGeometry(kCpuReference));
}

TEST(RenderExtremeGeometry, TransparentOpaqueAndRegionsBeyondTheCap) {
    test::report("transparent / opaque / capped", test::transparentOpaqueAndCappedRegions(kCpuReference));
}

TEST(RenderExtremeGeometry, IterationCapIsAnError) {
    test::report("iteration cap", test::iterationCapIsAnError(kCpuReference));
}

}  // namespace
}  // namespace vr
