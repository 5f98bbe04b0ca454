// A heap that keeps a rendered view's blocks for the next view of an orbit.
#pragma once

namespace vr {

// glibc maps each block of 128 KB or more afresh and unmaps it when freed, raising that threshold to the size of a
// freed mapping (up to 32 MB), and returns the free top of its heap to the kernel beyond twice the threshold. After a
// small volume every view's image, samples and iterations (7 MB at 512 x 512) then came in fresh pages, each faulted
// and zeroed again: 1.2-3.5 ms a view of the head CT on the 2-core machine, 2 ms of a 5 ms view on an H100. From this
// call on, blocks below 32 MB come from the heap, which keeps up to 16 MB free at its top: a 512 x 512 view's blocks.
// Called once the volume is prepared: set from the start, the stages' blocks kept on 16 cores' heaps added 24 MB to
// the cranium's peak.
void keepViewBlocksInTheHeap();

}  // namespace vr
