// DICOM checks before vtkDICOMImageReader, whose parser passes the null value of a zero-length element to strcmp
// or strtod and copies a whole slice out of pixel data shorter than rows x columns x bits allocated.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "preprocess/load/header_checks.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t tag(std::uint16_t group, std::uint16_t element) {
    return std::uint32_t(group) << 16 | element;
}

constexpr std::uint32_t kTransferSyntax = tag(0x0002, 0x0010), kPixelData = tag(0x7FE0, 0x0010),
                        kSamples = tag(0x0028, 0x0002), kRows = tag(0x0028, 0x0010), kColumns = tag(0x0028, 0x0011),
                        kBitsAllocated = tag(0x0028, 0x0100);

// Elements whose values VTK's DICOMAppHelper parses in callbacks without looking at their length.
bool parsedByVtk(std::uint32_t t) {
    switch (t) {
        case kTransferSyntax:
        case kSamples:
        case kRows:
        case kColumns:
        case kBitsAllocated:
        case tag(0x0018, 0x0050):
        case tag(0x0020, 0x0013):
        case tag(0x0020, 0x0032):
        case tag(0x0020, 0x0037):
        case tag(0x0020, 0x1041):
        case tag(0x0028, 0x0004):
        case tag(0x0028, 0x0030):
        case tag(0x0028, 0x0101):
        case tag(0x0028, 0x0102):
        case tag(0x0028, 0x0103):
        case tag(0x0028, 0x1052):
        case tag(0x0028, 0x1053): return true;
        default: return false;
    }
}

std::string tagText(std::uint32_t t) {
    char text[16];
    std::snprintf(text, sizeof text, "(%04X,%04X)", unsigned(t >> 16), unsigned(t & 0xFFFF));
    return text;
}

}  // namespace

void checkDicomFile(const fs::path& path) {
    const auto fail = [&](const std::string& problem) {
        return fileError(path.string(), "invalid DICOM file: " + problem);
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path.string(), "cannot open");
    std::error_code ec;
    const std::uint64_t size = fs::file_size(path, ec);
    char magic[4] = {};
    if (ec || !in.seekg(128) || !in.read(magic, 4) || std::string(magic, 4) != "DICM")
        throw fail("no \"DICM\" after the 128-byte preamble (only DICOM Part 10 files are supported)");

    const auto u16 = [](const unsigned char* b) { return std::uint16_t(b[0] | b[1] << 8); };
    const auto u32 = [](const unsigned char* b) {
        return std::uint32_t(b[0] | b[1] << 8 | b[2] << 16 | std::uint32_t(b[3]) << 24);
    };
    bool explicitVr = true;  // the file meta group (0002) always is; the transfer syntax tells the rest
    std::string transferSyntax;
    std::uint64_t rows = 0, columns = 0, bits = 0, samples = 1;
    for (std::uint64_t at = 132; at < size;) {
        unsigned char head[12];
        if (size - at < 8 || !in.seekg(std::streamoff(at)) || !in.read(reinterpret_cast<char*>(head), 8))
            throw fail("an element header is cut off at byte " + std::to_string(at));
        const std::uint32_t t = tag(u16(head), u16(head + 2));
        if (t >> 16 != 0x0002 && transferSyntax.empty()) throw fail("no transfer syntax (0002,0010)");
        if (t >> 16 != 0x0002) explicitVr = transferSyntax != "1.2.840.10008.1.2";
        std::uint64_t length;
        if (t >> 16 == 0xFFFE || !explicitVr) {  // items and delimiters have no VR
            length = u32(head + 4);
            at += 8;
        } else {
            const std::string vr(reinterpret_cast<const char*>(head + 4), 2);
            if (vr == "OB" || vr == "OW" || vr == "OF" || vr == "OD" || vr == "OL" || vr == "OV" || vr == "SQ" ||
                vr == "UT" || vr == "UN" || vr == "UC" || vr == "UR" || vr == "SV" || vr == "UV") {
                if (size - at < 12 || !in.read(reinterpret_cast<char*>(head + 8), 4))
                    throw fail("an element header is cut off at byte " + std::to_string(at));
                length = u32(head + 8);
                at += 12;
            } else {
                length = u16(head + 6);
                at += 8;
            }
        }
        // Undefined lengths open sequences and items, whose elements are walked like the others.
        if (length == 0xFFFFFFFF) {
            if (t == kPixelData) throw fail("compressed (encapsulated) pixel data are not supported");
            continue;
        }
        if (t >> 16 == 0xFFFE) continue;  // an item of defined length: its elements follow
        if (length > size - at)
            throw fail("element " + tagText(t) + " of " + std::to_string(length) +
                       " bytes runs past the end of the file");
        if (parsedByVtk(t) && length == 0) throw fail("element " + tagText(t) + " is empty");
        if (t == kPixelData) {
            if (rows == 0 || columns == 0 || bits == 0)
                throw fail("pixel data without rows, columns and bits allocated");
            const std::uint64_t needed = rows * columns * samples * ((bits + 7) / 8);
            if (length < needed)
                throw fail("pixel data hold " + std::to_string(length) +
                           " bytes but rows x columns x bits allocated need " + std::to_string(needed));
            return;
        }
        if (t == kTransferSyntax || t == kRows || t == kColumns || t == kBitsAllocated || t == kSamples) {
            std::string value(std::size_t(std::min<std::uint64_t>(length, 64)), '\0');
            in.seekg(std::streamoff(at));
            if (!in.read(value.data(), std::streamsize(value.size()))) throw fail("cannot read element " + tagText(t));
            const auto* b = reinterpret_cast<const unsigned char*>(value.data());
            if (t == kTransferSyntax) {
                while (!value.empty() && (value.back() == '\0' || value.back() == ' ')) value.pop_back();
                if (value != "1.2.840.10008.1.2" && value != "1.2.840.10008.1.2.1")
                    throw fail("transfer syntax \"" + value + "\" is not implicit or explicit VR little endian");
                transferSyntax = value;
            } else if (length >= 2) {
                (t == kRows ? rows : t == kColumns ? columns : t == kBitsAllocated ? bits : samples) = u16(b);
            }
        }
        at += length;
    }
    throw fail("no pixel data (7FE0,0010)");
}

}  // namespace vr
