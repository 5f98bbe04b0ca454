// The prepared file (format documented in docs/PREPARED_FORMAT.md): written atomically, read with checks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "core/progress.h"

namespace vr {

// 6: every per-voxel chunk stored as its bytes' differences from the slice before (compression.filter sliceDelta).
// 5: a label map beside the scalars (the labelMap header and its two chunks), where one was given.
// 4: every chunk compressed with zstd in independent blocks, each with the CRC-32 of its compressed bytes.
// 3: the scalars and the tabulated transfer function instead of the classified volume (sigma, colour, normal).
// 2: EACD chunks coded (eacdCode).
constexpr int kPreparedFormatVersion = 6;

// How writePrepared compresses: the zstd level (chosen by measurement, docs/PREPARED_FORMAT.md) and the bytes of a
// chunk (uncompressed) that each independent block holds, the last block of a chunk holding the rest.
constexpr int kPreparedZstdLevel = 1;
constexpr std::size_t kPreparedBlockBytes = std::size_t(4) << 20;
// The largest block the file may hold (uncompressed), a check on a damaged header.
constexpr std::size_t kMaxPreparedBlockBytes = std::size_t(1) << 30;

struct PreparedWriteOptions {
    int zstdLevel = kPreparedZstdLevel;          // ZSTD_minCLevel() .. ZSTD_maxCLevel(), 0 is zstd's default (3)
    std::size_t blockBytes = kPreparedBlockBytes;  // 1 .. kMaxPreparedBlockBytes
    Progress progress;                             // hears the share of the blocks compressed, then the write
};

// Largest transfer table the file holds (entries), a check on a damaged header before any allocation.
constexpr std::size_t kMaxTransferTableEntries = std::size_t(1) << 20;

// Throws InputError (naming the path) for arrays that do not fit the grid, and for scalars that the volume's own
// type cannot hold exactly (a fraction or an out-of-range value in an integer volume, or a non-finite value), and for
// options out of range. The chunks are compressed in parallel.
void writePrepared(const std::filesystem::path& path, const PreparedVolume& prepared,
                   const PreparedWriteOptions& options = {});

// What a read may leave out: a render needs neither the regions' labels nor the ACD and EACD octants its views'
// rays do not have (on a 512^3 CT, 512 MiB and 7 of the 8 octants for one view, each to inflate into fresh memory).
struct PreparedReadScope {
    unsigned octants = kAllOctants;  // the ACD and EACD octants read (bit o: octant o); the others stay empty
    bool regions = true;             // the regions' labels; without them Regions::label stays empty (the count is read)
    // false: integer scalars stay in their own type (Volume::stored, Volume::values empty), for a device upload that
    // needs nothing else of them (at 512^3 int16, 512 MiB of floats not made); float32 scalars are read as floats.
    bool floatScalars = true;
};

// Reads the scalars, the transfer table, the region labels, the label map where the file has one and only the
// distance fields in `fields` (a FieldKind mask), within `scope`: a render loads what its caster uses. Throws
// InputError for a foreign, truncated or inconsistent file.
PreparedVolume readPrepared(const std::filesystem::path& path, unsigned fields = kFieldPC | kFieldACD | kFieldEACD,
                            const PreparedReadScope& scope = {});

// One chunk as the chunk table describes it: its bytes in memory and in the file (compressed).
struct PreparedChunkBytes {
    std::string name;
    std::uint64_t bytes = 0;        // uncompressed
    std::uint64_t storedBytes = 0;  // its blocks, compressed
};

// What the header says of a prepared file, which is all --caster auto needs.
struct PreparedHeader {
    GridGeometry grid;
    ScalarType scalarType = ScalarType::Float32;  // of the scalars chunk
    std::size_t tableEntries = 0;                 // of the transfer table
    PreparedMetadata meta;
    FieldBytes fieldBytes;  // of the distance fields the file holds (0 for one it lacks), uncompressed
    std::vector<PreparedChunkBytes> chunks;  // every chunk, in the order of the chunk table
};

// The header, checked as readPrepared checks it, without reading any chunk. Throws InputError as readPrepared does
// for a bad header.
PreparedHeader readPreparedHeader(const std::filesystem::path& path);

// Whether `path` starts as a prepared file does (its magic): what tells a prepared file from a volume to prepare.
bool isPreparedFile(const std::filesystem::path& path);

}  // namespace vr
