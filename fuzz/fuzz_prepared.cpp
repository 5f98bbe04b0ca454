// The prepared file through readPrepared. The header's CRC-32 is made to match first: without that nearly every
// mutation of the header would stop at the checksum, and the header (JSON, chunk table) is what needs fuzzing. For
// every other input (by size) the blocks' CRC-32s in the header are made to match too, so that mutations of the
// blocks reach zstd, the blocks' size checks and the checks of the chunks' contents.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.h"
#include "io/prepared_file.h"
#include "fuzz/support.h"

namespace {

constexpr std::size_t kPreamble = 20;  // magic, u32 version, u64 header length (docs/PREPARED_FORMAT.md)

uint32_t crcOf(const char* data, std::size_t bytes) {
    return uint32_t(crc32_z(0, reinterpret_cast<const Bytef*>(data), bytes));
}

// The header length when the header and its CRC-32 lie inside the file, else 0.
uint64_t headerBytes(const std::string& bytes) {
    if (bytes.size() < kPreamble) return 0;
    uint64_t h;
    std::memcpy(&h, bytes.data() + 12, sizeof(h));
    return h <= bytes.size() - kPreamble && bytes.size() - kPreamble - h >= 4 ? h : 0;
}

void fixHeaderChecksum(std::string& bytes) {
    const uint64_t h = headerBytes(bytes);
    if (h == 0) return;
    const uint32_t crc = crcOf(bytes.data() + kPreamble, h);
    std::memcpy(bytes.data() + kPreamble + h, &crc, sizeof(crc));
}

// Sets each block's crc32 in the chunk table to the CRC-32 of the bytes it names (where they lie inside the file);
// the header is then written again, compact. Leaves a header that is not such JSON as it is.
void fixBlockChecksums(std::string& bytes) {
    const uint64_t h = headerBytes(bytes);
    if (h == 0) return;
    const uint64_t dataStart = kPreamble + h + 4;
    nlohmann::json header =
        nlohmann::json::parse(bytes.data() + kPreamble, bytes.data() + kPreamble + h, nullptr, false);
    if (header.is_discarded() || !header.is_object() || !header.contains("chunks") || !header["chunks"].is_array())
        return;
    for (nlohmann::json& chunk : header["chunks"]) {
        if (!chunk.is_object() || !chunk.contains("offset") || !chunk["offset"].is_number_unsigned() ||
            !chunk.contains("blocks") || !chunk["blocks"].is_array())
            continue;
        uint64_t at = chunk["offset"].get<uint64_t>();
        if (at > bytes.size()) continue;
        at += dataStart;
        for (nlohmann::json& block : chunk["blocks"]) {
            if (!block.is_object() || !block.contains("compressedBytes") ||
                !block["compressedBytes"].is_number_unsigned())
                break;
            const uint64_t n = block["compressedBytes"].get<uint64_t>();
            if (at > bytes.size() || n > bytes.size() - at) break;
            block["crc32"] = crcOf(bytes.data() + at, n);
            at += n;
        }
    }
    const std::string text = header.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    const uint64_t length = text.size();
    std::string out = bytes.substr(0, 12);
    out.append(reinterpret_cast<const char*>(&length), sizeof(length));
    out += text;
    out.append(4, '\0');  // the header's CRC-32, set after
    out.append(bytes, dataStart, std::string::npos);
    bytes = std::move(out);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    if (size & 8) fixBlockChecksums(bytes);
    fixHeaderChecksum(bytes);
    const std::filesystem::path path = vr::fuzz::writeInput("input.vprep", bytes);
    // The input's size picks which distance fields are read, and whether as a render on the device reads them (some
    // octants, no region labels, integer scalars in their own type), so that every chunk is fuzzed both read and
    // skipped, the scalars both as floats and as their bytes.
    const unsigned fields = unsigned(size % 8);
    vr::PreparedReadScope scope;
    if (size & 16) scope = {unsigned(size >> 5) & vr::kAllOctants, false, (size & 8192) != 0};
    try {
        const vr::PreparedVolume p = vr::readPrepared(path, fields, scope);
        const std::size_t voxels = p.grid().voxels();
        const vr::TransferTable& table = p.classification.table;
        const vr::Volume& s = p.scalars;
        if (!s.values.empty() && !s.stored.empty())
            vr::fuzz::finding("readPrepared returned the scalars both as floats and in their own type");
        if (vr::heldVoxels(s) != voxels || p.regions.label.size() != (scope.regions ? voxels : 0))
            vr::fuzz::finding("readPrepared returned arrays that do not fit the grid");
        if (table.sigma.size() != table.colour.size() || table.size() < 1 ||
            table.size() > vr::kMaxTransferTableEntries)
            vr::fuzz::finding("readPrepared returned a transfer table of a bad size");
        if (!(table.step > 0) || !(p.classification.referenceStep > 0) || !(p.classification.flatGradient >= 0))
            vr::fuzz::finding("readPrepared returned a classification that cannot be rendered");
        if (!std::all_of(p.scalars.values.begin(), p.scalars.values.end(), [](float v) { return std::isfinite(v); }))
            vr::fuzz::finding("readPrepared returned a scalar that is not finite");
        if (std::any_of(p.regions.label.begin(), p.regions.label.end(),
                        [&](uint32_t l) { return l >= p.regions.count; }))
            vr::fuzz::finding("readPrepared returned a label beyond the region count");
    } catch (const vr::InputError&) {
    }
    return 0;
}
