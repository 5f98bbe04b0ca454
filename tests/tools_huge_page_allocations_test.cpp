// Large blocks from operator new are advised onto transparent huge pages (tools/huge_page_allocations.cpp): the
// kernel marks the mapping holding them "hg" in /proc/self/smaps.
#include <gtest/gtest.h>

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

}  // namespace
