// Large blocks from operator new are advised onto transparent huge pages (tools/huge_page_allocations.cpp): the
// kernel marks the mapping holding them "hg" in /proc/self/smaps. A view's blocks are reused by the next view
// without faulting their pages again (tools/heap_reuse.cpp).
#include <gtest/gtest.h>
#include <malloc.h>
#include <sys/resource.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

// The VmFlags of the mapping of /proc/self/smaps that holds address a ("" if none does).
std::string vmFlagsAt(std::uintptr_t a) {
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t lo = 0, hi = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> lo >> dash >> hi && dash == '-' && line.find(':') > line.find(' ')) {
            inside = lo <= a && a < hi;
        } else if (inside && line.rfind("VmFlags:", 0) == 0) {
            return line;
        }
    }
    return "";
}

bool hasFlag(const std::string& vmFlags, const std::string& flag) {
    return (vmFlags + " ").find(" " + flag + " ") != std::string::npos;
}

TEST(ToolsHugePageAllocations, LargeBlocksAreAdvised) {
#ifndef VR_HUGE_PAGE_ALLOCATIONS
    GTEST_SKIP() << "sanitizer build: the sanitizer's operator new is in use";
#endif
    if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) GTEST_SKIP() << "kernel without THP";
    std::vector<uint8_t> large(std::size_t(16) << 20);
    const std::string flags = vmFlagsAt(reinterpret_cast<std::uintptr_t>(large.data()) + large.size() / 2);
    ASSERT_FALSE(flags.empty()) << "no mapping holds the block";
    EXPECT_TRUE(hasFlag(flags, "hg")) << flags;
}

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

TEST(ToolsHugePageAllocations, AViewsBlocksAreReusedWithoutFaultingTheirPagesAgain) {
#ifndef VR_HUGE_PAGE_ALLOCATIONS
    GTEST_SKIP() << "sanitizer build: the sanitizer's allocator is in use";
#endif
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
