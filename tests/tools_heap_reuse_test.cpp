// After keepViewBlocksInTheHeap (tools/heap_reuse.h), a view's blocks come from the heap and the next view reuses
// them without faulting their pages again.
#include "tools/heap_reuse.h"

#include <gtest/gtest.h>
#include <malloc.h>
#include <sys/resource.h>

#include <cstdint>
#include <vector>

namespace {

// Pages faulted by this process so far.
long minorFaults() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}

// What a 512 x 512 view allocates for its result: the image, the samples and the iterations per pixel (7 MB).
float renderAView() {
    std::vector<float> image(std::size_t(512) * 512 * 4, 0.0f);
    std::vector<uint64_t> samples(std::size_t(512) * 512, 0);
    std::vector<uint32_t> iterations(std::size_t(512) * 512, 0);
    return image[7] + float(samples[9] + iterations[3]);
}

TEST(ToolsHeapReuse, AViewsBlocksAreReusedWithoutFaultingTheirPagesAgain) {
#ifndef VR_HUGE_PAGE_ALLOCATIONS
    GTEST_SKIP() << "sanitizer build: the sanitizer's allocator is in use";
#endif
    vr::keepViewBlocksInTheHeap();
    // A block of 24 MB, bigger than any this process freed before, which glibc's own rule would map afresh.
    const std::size_t mappedBefore = mallinfo2().hblks;
    std::vector<uint8_t> block(std::size_t(24) << 20, 1);
    EXPECT_EQ(mallinfo2().hblks, mappedBefore) << "a 24 MB block was mapped on its own";
    block = {};
    float sum = renderAView();
    const long before = minorFaults();
    sum += renderAView();
    // Its pages are the first view's: mapped afresh, or returned to the kernel, they faulted about 500 times.
    EXPECT_LT(minorFaults() - before, 32) << sum;
}

}  // namespace
