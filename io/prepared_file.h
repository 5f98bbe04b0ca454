// The prepared file (format documented in docs/PREPARED_FORMAT.md): written atomically, read with checks.
#pragma once
#include <cstddef>
#include <filesystem>

#include "core/prepared_volume.h"

namespace vr {

// 3: the scalars and the tabulated transfer function instead of the classified volume (sigma, colour, normal).
// 2: EACD chunks coded (eacdCode).
constexpr int kPreparedFormatVersion = 3;

// Largest transfer table the file holds (entries), a check on a damaged header before any allocation.
constexpr std::size_t kMaxTransferTableEntries = std::size_t(1) << 20;

// Throws InputError (naming the path) for arrays that do not fit the grid, and for scalars that the volume's own
// type cannot hold exactly (a fraction or an out-of-range value in an integer volume, or a non-finite value).
void writePrepared(const std::filesystem::path& path, const PreparedVolume& prepared);

// Reads the scalars, the transfer table, the labels and only the distance fields in `fields` (a FieldKind mask):
// a render loads what its caster uses. Throws InputError for a foreign, truncated or inconsistent file.
PreparedVolume readPrepared(const std::filesystem::path& path, unsigned fields = kFieldPC | kFieldACD | kFieldEACD);

// What the header says of a prepared file, which is all --caster auto needs.
struct PreparedHeader {
    GridGeometry grid;
    ScalarType scalarType = ScalarType::Float32;  // of the scalars chunk
    std::size_t tableEntries = 0;                 // of the transfer table
    PreparedMetadata meta;
    FieldBytes fieldBytes;  // of the distance fields the file holds (0 for one it lacks)
};

// The header, checked as readPrepared checks it, without reading any chunk. Throws InputError as readPrepared does
// for a bad header.
PreparedHeader readPreparedHeader(const std::filesystem::path& path);

// Whether `path` starts as a prepared file does (its magic): what tells a prepared file from a volume to prepare.
bool isPreparedFile(const std::filesystem::path& path);

}  // namespace vr
