// A heap that keeps a rendered view's blocks for the next view. glibc maps each block of 128 KB or more afresh and
// unmaps it when freed, raising that threshold to the size of a freed mapping (up to 32 MB), and returns the free
// top of its heap to the kernel beyond twice the threshold. After a small volume, every view's image, samples and
// iterations (7 MB at 512 x 512) then came in fresh pages, each page faulted and zeroed again: 1.2-3.5 ms a view of
// the head CT against 0.6 ms after the cranium (2-core machine), where a freed volume had raised the threshold. Set
// from the start to where that rule ends, blocks below 32 MB come from the heap, and a heap keeps up to 16 MB free
// at its top: a 512 x 512 view's blocks, not what a volume's stages free (a heap per thread kept up to 64 MB added
// 20-24 MB to the peak of a one-view render on 16 cores). Larger blocks (volumes) are still mapped and returned.
#include <malloc.h>

namespace {

const bool heapKeepsViews = [] {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 16 << 20);
    return true;
}();

}  // namespace
