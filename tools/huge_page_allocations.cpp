// Large allocations on transparent huge pages (tools/huge_pages.h). Preprocessing allocates and frees volumes of
// hundreds of MB at a time, and a threshold or transfer-function change allocates them again. glibc can advise its
// blocks itself (the glibc.malloc.hugetlb tunable) but reads that only from the environment at start-up, so every
// program of the project replaces operator new (under every std::vector of ordinarily aligned elements) to advise
// them: a 512^3 threshold change takes 5.2-6.4 s instead of 7.8-8.5 (scaling_bench). Sanitizer builds keep their
// own operator new (theirs checks that new is paired with delete).
#include <cstdlib>
#include <new>

#include "tools/huge_pages.h"

namespace {

// Smaller blocks hold no whole huge page.
constexpr std::size_t kAdviseFrom = std::size_t(2) << 20;

}  // namespace

// The library's nothrow and array forms call this one; the library's operator delete calls free(), which matches.
void* operator new(std::size_t size) {
    void* p = std::malloc(size ? size : 1);
    if (!p) throw std::bad_alloc();
    if (size >= kAdviseFrom) vr::adviseHugePages(p, size);
    return p;
}
