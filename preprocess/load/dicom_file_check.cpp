// DICOM checks before vtkDICOMImageReader. Its parser (VTK's DICOMParser) walks a file its own way: from byte 4
// (magic at 0) or 132 (magic after the preamble) to the end of the file, past the pixel data, deciding each
// element's encoding by whether the two bytes after the tag spell a VR it knows, whatever the transfer syntax says.
// It hands a callback the null pointer for an element of length <= 0, which most of DICOMAppHelper's callbacks
// dereference (strcmp, strtod, a 2-byte read), and its pixel data callback copies rows x columns x bits allocated
// bytes whatever the element holds. So the check walks every file exactly as that parser does.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/header_checks.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t tag(std::uint16_t group, std::uint16_t element) {
    return std::uint32_t(group) << 16 | element;
}

constexpr std::uint32_t kTransferSyntax = tag(0x0002, 0x0010), kPixelData = tag(0x7FE0, 0x0010),
                        kSamples = tag(0x0028, 0x0002), kPhotometric = tag(0x0028, 0x0004),
                        kRows = tag(0x0028, 0x0010), kColumns = tag(0x0028, 0x0011),
                        kBitsAllocated = tag(0x0028, 0x0100);

// Elements with a callback in VTK 9.1's DICOMAppHelper (RegisterCallbacks, RegisterPixelDataCallback) or
// DICOMParser (the transfer syntax). The parser reads their values; an empty one reaches the callback as null.
enum class Callback { None, NullSafe, NeedsValue };

Callback callbackOf(std::uint32_t t) {
    switch (t) {
        case tag(0x0020, 0x0013):  // slice number
        case tag(0x0020, 0x0032):  // image position
        case tag(0x0020, 0x0037):  // image orientation
        case tag(0x0028, 0x0030):  // pixel spacing
        case tag(0x0010, 0x0010):  // patient name
        case tag(0x0020, 0x0010):  // study ID
        case tag(0x0018, 0x1120):  // gantry angle
            return Callback::NullSafe;
        case kTransferSyntax:
        case kPhotometric:
        case kRows:
        case kColumns:
        case kBitsAllocated:
        case kPixelData:
        case tag(0x0018, 0x0050):  // slice thickness
        case tag(0x0020, 0x000D):  // study UID
        case tag(0x0020, 0x000E):  // series UID
        case tag(0x0020, 0x1041):  // slice location
        case tag(0x0028, 0x0103):  // pixel representation
        case tag(0x0028, 0x1052):  // rescale intercept
        case tag(0x0028, 0x1053):  // rescale slope
            return Callback::NeedsValue;
        default: return Callback::None;
    }
}

// The two bytes after a tag as DICOMParser::IsValidRepresentation reads them: a VR with a 2-byte length, one with
// 2 reserved bytes and a 4-byte length, or no VR (the 4 bytes are the length).
enum class Encoding { ShortLength, LongLength, NoVr };

Encoding encodingOf(char a, char b) {
    static constexpr std::array<const char*, 23> shortVrs = {"AW", "AE", "AS", "CS", "UI", "DA", "DS", "DT",
                                                               "IS", "LO", "LT", "PN", "ST", "TM", "UT", "SH",
                                                               "FL", "SL", "AT", "UL", "US", "SS", "FD"};
    static constexpr std::array<const char*, 4> longVrs = {"OB", "OW", "UN", "SQ"};
    for (const char* vr : shortVrs)
        if (vr[0] == a && vr[1] == b) return Encoding::ShortLength;
    for (const char* vr : longVrs)
        if (vr[0] == a && vr[1] == b) return Encoding::LongLength;
    return Encoding::NoVr;
}

std::string tagText(std::uint32_t t) {
    char text[16];
    std::snprintf(text, sizeof text, "(%04X,%04X)", unsigned(t >> 16), unsigned(t & 0xFFFF));
    return text;
}

std::string trimmed(std::string value) {
    while (!value.empty() && (value.back() == '\0' || value.back() == ' ')) value.pop_back();
    return value;
}

}  // namespace

DicomSliceLayout checkDicomFile(const fs::path& path) {
    const auto fail = [&](const std::string& problem) {
        return fileError(path.string(), "invalid DICOM file: " + problem);
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fileError(path.string(), "cannot open");
    std::error_code ec;
    const std::uint64_t size = fs::file_size(path, ec);
    if (ec) throw fileError(path.string(), "cannot read its size");
    const auto readAt = [&](std::uint64_t at, std::size_t count) {
        std::string bytes(count, '\0');
        if (!in.seekg(std::streamoff(at)) || !in.read(bytes.data(), std::streamsize(count)))
            throw fail("cannot read " + std::to_string(count) + " bytes at byte " + std::to_string(at));
        return bytes;
    };
    const auto u16 = [](const std::string& b, std::size_t i) {
        return std::uint16_t(std::uint8_t(b[i]) | std::uint8_t(b[i + 1]) << 8);
    };
    const auto i32 = [](const std::string& b, std::size_t i) {
        return std::int32_t(std::uint32_t(std::uint8_t(b[i])) | std::uint32_t(std::uint8_t(b[i + 1])) << 8 |
                            std::uint32_t(std::uint8_t(b[i + 2])) << 16 | std::uint32_t(std::uint8_t(b[i + 3])) << 24);
    };

    std::uint64_t at;
    if (size >= 4 && readAt(0, 4) == "DICM")
        at = 4;
    else if (size >= 132 && readAt(128, 4) == "DICM")
        at = 132;
    else
        throw fail("no \"DICM\" after the 128-byte preamble (only DICOM Part 10 files are supported)");

    std::uint64_t rows = 0, columns = 0, bits = 0, samples = 1, rgb = 0;
    bool transferSyntaxSeen = false, pixelDataSeen = false;
    while (at < size) {
        if (size - at < 8) throw fail("an element header is cut off at byte " + std::to_string(at));
        std::string head = readAt(at, 8);
        const std::uint32_t t = tag(u16(head, 0), u16(head, 2));
        std::int64_t length;  // DICOMParser's quadbyte is an int: lengths of 2^31 or more are negative
        switch (encodingOf(head[4], head[5])) {
            case Encoding::ShortLength:
                length = u16(head, 6);
                at += 8;
                break;
            case Encoding::LongLength:
                if (size - at < 12) throw fail("an element header is cut off at byte " + std::to_string(at));
                length = i32(readAt(at + 8, 4), 0);
                at += 12;
                break;
            case Encoding::NoVr:
                length = i32(head, 4);
                at += 8;
                break;
        }
        const Callback callback = callbackOf(t);
        if (pixelDataSeen && callback == Callback::NeedsValue)
            throw fail("element " + tagText(t) + " follows the pixel data");
        if (length <= 0) {
            if (t == kPixelData && length == -1) throw fail("compressed (encapsulated) pixel data are not supported");
            if (callback == Callback::NeedsValue) throw fail("element " + tagText(t) + " is empty");
            continue;  // the parser neither reads nor skips anything
        }
        if (std::uint64_t(length) > size - at)
            throw fail("element " + tagText(t) + " of " + std::to_string(length) +
                       " bytes runs past the end of the file");
        if (t == kPixelData) {
            if (rows == 0 || columns == 0 || bits == 0)
                throw fail("pixel data without rows, columns and bits allocated before them");
            const std::uint64_t needed = rows * columns * std::max(samples, rgb) * (bits / 8);
            if (std::uint64_t(length) < needed)
                throw fail("pixel data hold " + std::to_string(length) +
                           " bytes but rows x columns x samples x bits allocated need " + std::to_string(needed));
            pixelDataSeen = true;
        } else if (t == kTransferSyntax) {
            const std::string value = trimmed(readAt(at, std::size_t(std::min<std::int64_t>(length, 64))));
            if (value != "1.2.840.10008.1.2" && value != "1.2.840.10008.1.2.1")
                throw fail("transfer syntax \"" + value + "\" is not implicit or explicit VR little endian");
            transferSyntaxSeen = true;
        } else if (t == kPhotometric) {
            rgb = trimmed(readAt(at, std::size_t(std::min<std::int64_t>(length, 16)))).rfind("RGB", 0) == 0 ? 3 : 1;
        } else if (t == kRows || t == kColumns || t == kBitsAllocated || t == kSamples) {
            if (length < 2) throw fail("element " + tagText(t) + " holds " + std::to_string(length) + " byte");
            (t == kRows ? rows : t == kColumns ? columns : t == kBitsAllocated ? bits : samples) =
                u16(readAt(at, 2), 0);
            if (t == kBitsAllocated && bits != 8 && bits != 16)
                throw fail(std::to_string(bits) + " bits allocated (VTK's DICOM reader reads 8 or 16)");
        }
        at += std::uint64_t(length);
    }
    if (!transferSyntaxSeen) throw fail("no transfer syntax (0002,0010)");
    if (!pixelDataSeen) throw fail("no pixel data (7FE0,0010)");
    return {rows, columns, bits, std::max(samples, rgb)};
}

}  // namespace vr
