// Transparent huge pages on request. Where the kernel grants them only to memory advised for them (THP mode
// "madvise", Debian's default), fresh memory is otherwise faulted in 4 KiB at a time as it is first written:
// 0.35-1.1 s per GB on this project's build VM against 0.05 s per GB on 2 MiB pages.
#pragma once
#include <cstddef>

namespace vr {

// Advises the whole pages inside [data, data + bytes) for huge pages; call it before the memory is first written.
// A hint only: where it is refused nothing changes.
void adviseHugePages(void* data, std::size_t bytes);

}  // namespace vr
