// The prepared file through readPrepared. The header's CRC-32 is made to match first: without that nearly every
// mutation of the header would stop at the checksum, and the header (JSON, chunk table) is what needs fuzzing.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/errors.h"
#include "io/prepared_file.h"
#include "fuzz/support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    constexpr std::size_t preamble = 20;  // magic, u32 version, u64 header length (docs/PREPARED_FORMAT.md)
    if (bytes.size() >= preamble) {
        uint64_t headerBytes;
        std::memcpy(&headerBytes, bytes.data() + 12, sizeof(headerBytes));
        if (headerBytes <= bytes.size() - preamble && bytes.size() - preamble - headerBytes >= 4) {
            const uint32_t crc = uint32_t(crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data() + preamble), headerBytes));
            std::memcpy(bytes.data() + preamble + headerBytes, &crc, sizeof(crc));
        }
    }
    const std::filesystem::path path = vr::fuzz::writeInput("input.vprep", bytes);
    // The input's size picks which distance fields are read, so that they are fuzzed both read and skipped.
    const unsigned fields = unsigned(size % 8);
    try {
        const vr::PreparedVolume p = vr::readPrepared(path, fields);
        const std::size_t voxels = p.grid().voxels();
        const vr::TransferTable& table = p.classification.table;
        if (p.scalars.values.size() != voxels || p.regions.label.size() != voxels)
            vr::fuzz::finding("readPrepared returned arrays that do not fit the grid");
        if (table.sigma.size() != table.colour.size() || table.size() < 1 || table.size() > vr::kMaxTransferTableEntries)
            vr::fuzz::finding("readPrepared returned a transfer table of a bad size");
        if (!(table.step > 0) || !(p.classification.referenceStep > 0) || !(p.classification.flatGradient >= 0))
            vr::fuzz::finding("readPrepared returned a classification that cannot be rendered");
        if (!std::all_of(p.scalars.values.begin(), p.scalars.values.end(), [](float v) { return std::isfinite(v); }))
            vr::fuzz::finding("readPrepared returned a scalar that is not finite");
    } catch (const vr::InputError&) {
    }
    return 0;
}
