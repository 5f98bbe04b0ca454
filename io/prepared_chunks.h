// What the prepared file's writer and reader share (io/prepared_file_write.cpp, io/prepared_file_read.cpp): the
// magic, the layout of each chunk and how the scalars and tables are coded in it. Internal to io/.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/extent_code.h"
#include "core/prepared_volume.h"

namespace vr::prepared_detail {

// Chunks are stored as the in-memory arrays, so the file is little-endian only where the machine is.
static_assert(std::endian::native == std::endian::little, "the prepared format is little-endian");

inline constexpr char kMagic[8] = {'V', 'O', 'L', 'P', 'R', 'E', 'P', '\0'};
// How the per-voxel chunks are coded before zstd (io/slice_delta.h).
inline constexpr const char* kSliceDeltaFilter = "sliceDelta";
// A table entry in the file: r, g, b, sigma (a label table's too).
inline constexpr int kTableComponents = 4;
// A label map's classes: one per label 0..65535 at most.
inline constexpr std::size_t kMaxLabelEntries = std::size_t(1) << 16;

// What a chunk of a given name must hold: its element type and components per voxel (per entry for the table).
struct ChunkLayout {
    std::string type;  // empty: no such chunk
    int components;
    std::size_t elementBytes;
};

ChunkLayout layoutOf(const std::string& name, ExtentCode eacdCode, ScalarType scalarType, ScalarType labelType);

bool isTableChunk(const std::string& name);

// The bytes of one z slice of a chunk: a per-voxel chunk is stored as its differences over slices
// (io/slice_delta.h); 0 for the tables, stored as they are.
uint64_t sliceBytesOf(const std::string& name, const ChunkLayout& l, const Vec3i& dims);

// The scalars in the file's type, encoded on all threads; returns the first voxel whose scalar the type does not
// hold exactly (narrowScalars), or values.size().
std::size_t encodeScalars(const std::vector<float>& values, ScalarType t, std::vector<char>& bytes);
// The scalars of the file's type t in `bytes` as floats in `values` (sized by the caller); a float32 chunk is read
// straight into the values and left as it is.
void decodeScalars(const std::vector<char>& bytes, ScalarType t, std::vector<float>& values);

// A table chunk's entries (kTableComponents floats each) as a table's sigma and colour (a label map's classes too).
void splitTable(const std::vector<float>& in, TransferTable& t);

}  // namespace vr::prepared_detail
