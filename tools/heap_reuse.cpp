#include "tools/heap_reuse.h"

#include <malloc.h>

namespace vr {

void keepViewBlocksInTheHeap() {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 16 << 20);
}

}  // namespace vr
