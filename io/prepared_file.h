// The prepared file (format documented in docs/PREPARED_FORMAT.md): written atomically, read with checks.
#pragma once
#include <filesystem>

#include "core/prepared_volume.h"

namespace vr {

constexpr int kPreparedFormatVersion = 2;  // 2: EACD chunks coded (eacdCode)

void writePrepared(const std::filesystem::path& path, const PreparedVolume& prepared);

// Reads only the distance fields in `fields` (a FieldKind mask) and normals only if `normals`:
// a render loads what its caster uses. Throws InputError for a foreign, truncated or inconsistent file.
PreparedVolume readPrepared(const std::filesystem::path& path, unsigned fields = kFieldPC | kFieldACD | kFieldEACD,
                            bool normals = true);

// What the header says of a prepared file, which is all --caster auto needs.
struct PreparedHeader {
    GridGeometry grid;
    PreparedMetadata meta;
    FieldBytes fieldBytes;  // of the distance fields the file holds (0 for one it lacks)
};

// The header, checked as readPrepared checks it, without reading any chunk. Throws InputError as readPrepared does
// for a bad header.
PreparedHeader readPreparedHeader(const std::filesystem::path& path);

}  // namespace vr
