// The prepared file's per-voxel chunks are stored, block by block, as each byte's difference (mod 256) from the
// byte one z slice before it in the same block (docs/PREPARED_FORMAT.md, Compression): distance fields, region ids
// and scalars change little from slice to slice, so the differences are mostly zeros, which zstd packs 1.6-1.8x
// tighter than the arrays themselves. A block's first slice is stored as it is, so blocks stay independent: each
// one is decoded as soon as it is decompressed, while its bytes are still in the cache.
#pragma once
#include <cstdint>

namespace vr {

// The differences of a block of `bytes` bytes, in a chunk of slices of sliceBytes > 0.
void sliceDeltaEncode(const unsigned char* block, uint64_t bytes, uint64_t sliceBytes, unsigned char* differences);

// A block's differences turned back into its bytes, in place.
void sliceDeltaDecode(unsigned char* block, uint64_t bytes, uint64_t sliceBytes);

}  // namespace vr
