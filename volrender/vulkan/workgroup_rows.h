// The order in which a dispatch's rows of workgroups take the tile's rows of pixels.
#pragma once

namespace vr {

// llvmpipe (lavapipe) hands each of its threads one contiguous run of a dispatch's workgroups, in order (x fastest):
// with 2 threads, one takes the tile's upper half and the other its lower half, and where one half holds more of the
// volume its thread works on alone at the end. Workgroup row r takes pixel row (r * stride) mod rows instead: with a
// stride near rows / golden ratio and coprime with rows, every run of consecutive workgroup rows is spread over the
// whole tile (a rank-1 lattice), whatever the number of threads. GPUs, which take workgroups one at a time, keep the
// order (a stride of 1: VulkanRenderer asks for this one on CPU devices only).
int interleavedRowStride(int rows);

}  // namespace vr
