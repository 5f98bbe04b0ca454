// Large allocations on transparent huge pages. Preprocessing allocates and frees volumes of hundreds of MB at a
// time, and a threshold or transfer-function change allocates them again; mapping fresh memory 4 KiB at a time is
// a large part of that cost where the kernel gives huge pages only on request (THP "madvise", Debian's default):
// 0.35-1.1 s per GB on this project's build VM, against 0.05 s per GB on 2 MiB pages. glibc can ask for them
// itself (the glibc.malloc.hugetlb tunable) but reads that only from the environment at start-up, so every
// program of the project replaces operator new (under every std::vector of ordinarily aligned elements) to ask
// for them: a 512^3 threshold change takes 5.2-6.4 s instead of 7.8-8.5 (scaling_bench). Sanitizer builds keep
// their own operator new (theirs checks that new is paired with delete).
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

// The 2 MiB pages wholly inside [p, p + size) come on huge pages when first touched (advice only: it may fail).
// Blocks glibc carves from its heap are advised too: that heap's pages are then reused on huge pages as well.
void adviseHugePages(void* p, std::size_t size) {
    const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(p) + size) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

}  // namespace

// The library's nothrow and array forms call this one; the library's operator delete calls free(), which matches.
void* operator new(std::size_t size) {
    void* p = std::malloc(size ? size : 1);
    if (!p) throw std::bad_alloc();
    if (size >= kHugePage) adviseHugePages(p, size);
    return p;
}
