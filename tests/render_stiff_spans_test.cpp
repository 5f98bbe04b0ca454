// The stiff numerics of docs/ALGORITHMS.md section 6 on the CPU reference: span opacity from 1e-12 to 1 over spans of
// 1 to 1e7 samples, long rays through many thin regions and one huge region against double-precision answers,
// steps from 1/64 to 4 voxels with samples on voxel faces, and early termination hit exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/classified_volume.h"
#include "support/render_cases.h"
#include "render/span.h"

namespace vr {
namespace {

using test::kCpuReference;

// The span function itself, from the stored (float) extinction as the renderer calls it: 1 - (1 - alpha)^N.
TEST(RenderStiffSpans, SpanFunctionOverTheOpacityAndLengthGrid) {
    int tried = 0;
    for (const double n : {1.0, 10.0, 1e4, 1e7})
        for (const double alpha : {0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.5, 1 - 1e-7, 1.0}) {
            const double dt = 1 / n;
            const double sigma = float(extinctionFromOpacity(alpha, dt));
            const double got = spanOpacity(sigma, n * dt);
            ++tried;
            if (alpha == 0) {
                EXPECT_EQ(got, 0.0);
            } else if (alpha == 1) {
                EXPECT_EQ(float(got), 1.0f) << "N " << n;
            } else {
                const double want = -std::expm1(n * std::log1p(-alpha));
                EXPECT_LT(std::abs(got - want) / want, 1e-4) << "alpha " << alpha << " N " << n;
            }
        }
    std::printf("span function: %d inputs\n", tried);
}

TEST(RenderStiffSpans, RenderedSpanOpacityOverTheOpacityAndLengthGrid) {
    test::report("span opacity grid", test::spanOpacityGrid(kCpuReference, {}));
}

TEST(RenderStiffSpans, ThinSlabsMatchTheLatticeSum) {
    test::report("thin slabs", test::thinSlabsAgainstTheLatticeSum(kCpuReference, {}));
}

TEST(RenderStiffSpans, HugeRegionMatchesTheClosedForm) {
    test::report("huge region", test::hugeRegionAgainstTheClosedForm(kCpuReference, {}));
}

TEST(RenderStiffSpans, EarlyTerminationHitExactly) {
    test::report("ert hit exactly", test::earlyTerminationHitExactly(kCpuReference));
}

}  // namespace
}  // namespace vr
