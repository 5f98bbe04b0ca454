#include "tools/huge_pages.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>

namespace vr {

void adviseHugePages(void* data, std::size_t bytes) {
    const auto page = std::uintptr_t(sysconf(_SC_PAGESIZE)), begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t lo = (begin + page - 1) & ~(page - 1), hi = (begin + bytes) & ~(page - 1);
    if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
}

}  // namespace vr
