// DICOM checks before vtkDICOMImageReader. Its parser (VTK's DICOMParser) walks a file its own way: from byte 4
// (magic at 0) or 132 (magic after the preamble) to the end of the file, past the pixel data, deciding each
// element's encoding by whether the two bytes after the tag spell a VR it knows, whatever the transfer syntax says.
// It hands a callback the null pointer for an element of length <= 0, which most of DICOMAppHelper's callbacks
// dereference (strcmp, strtod, a 2-byte read), and its pixel data callback copies rows x columns x components x
// bits allocated bytes whatever the element holds (components: 3 for an "RGB " photometric interpretation, else 1,
// whatever the samples per pixel say). So the check walks every file exactly as that parser does.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <string>

#include "preprocess/load/bounded_reader.h"
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
                        kBitsAllocated = tag(0x0028, 0x0100), kSeriesUid = tag(0x0020, 0x000E);

// Whether the element has a callback in VTK 9.1's DICOMAppHelper (RegisterCallbacks, RegisterPixelDataCallback) or
// DICOMParser (the transfer syntax) that uses its value: the parser hands an empty value to the callback as null.
// (The callbacks of slice number, image position and orientation, pixel spacing, patient name, study ID and
// gantry angle take null.)
bool needsValue(std::uint32_t t) {
    switch (t) {
        case kTransferSyntax:
        case kPhotometric:
        case kRows:
        case kColumns:
        case kBitsAllocated:
        case kPixelData:
        case tag(0x0018, 0x0050):  // slice thickness
        case tag(0x0020, 0x000D):  // study UID
        case kSeriesUid:
        case tag(0x0020, 0x1041):  // slice location
        case tag(0x0028, 0x0103):  // pixel representation
        case tag(0x0028, 0x1052):  // rescale intercept
        case tag(0x0028, 0x1053):  // rescale slope
            return true;
        default: return false;
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

// A value without the NULs and spaces that pad it to an even length.
std::string unpadded(std::string value) {
    while (!value.empty() && (value.back() == '\0' || value.back() == ' ')) value.pop_back();
    return value;
}

}  // namespace

DicomSlice checkDicomFile(const fs::path& path) {
    BoundedReader file(path, "invalid DICOM file");
    const auto magicAt = [&](std::uint64_t at) {
        if (file.size() < at + 4) return false;
        file.seek(at, "the magic");
        return file.bytes(4, "the magic") == "DICM";
    };
    if (!magicAt(0) && !magicAt(128))
        throw file.fail("no \"DICM\" after the 128-byte preamble (only DICOM Part 10 files are supported)");

    std::uint64_t rows = 0, columns = 0, bits = 0, samples = 1, rgb = 0;
    std::string seriesUid;
    bool transferSyntaxSeen = false, pixelDataSeen = false;
    while (file.remaining() > 0) {
        const std::uint64_t start = file.position();
        const auto cutOff = [&] { return file.fail("an element header is cut off at byte " + std::to_string(start)); };
        if (file.remaining() < 8) throw cutOff();
        const std::uint16_t group = file.littleEndian<std::uint16_t>("an element's tag");
        const std::uint32_t t = tag(group, file.littleEndian<std::uint16_t>("an element's tag"));
        const std::string vr = file.bytes(4, "an element header");  // or, without a VR, the length
        std::int64_t length;  // DICOMParser's quadbyte is an int: lengths of 2^31 or more are negative
        switch (encodingOf(vr[0], vr[1])) {
            case Encoding::ShortLength: length = valueAt<std::uint16_t>(vr, 2); break;
            case Encoding::LongLength:
                if (file.remaining() < 4) throw cutOff();
                length = file.littleEndian<std::int32_t>("an element header");
                break;
            case Encoding::NoVr: length = valueAt<std::int32_t>(vr, 0); break;
        }
        const std::string what = "element " + tagText(t);
        const bool valueNeeded = needsValue(t);
        if (pixelDataSeen && valueNeeded) throw file.fail(what + " follows the pixel data");
        if (length <= 0) {
            if (t == kPixelData && length == -1)
                throw file.fail("compressed (encapsulated) pixel data are not supported");
            if (valueNeeded) throw file.fail(what + " is empty");
            continue;  // the parser neither reads nor skips anything
        }
        if (std::uint64_t(length) > file.remaining())
            throw file.fail(what + " of " + std::to_string(length) + " bytes runs past the end of the file");
        const std::uint64_t end = file.position() + std::uint64_t(length);
        // The value's first `most` bytes as text, without its padding.
        const auto text = [&](std::int64_t most) {
            return unpadded(file.bytes(std::size_t(std::min(length, most)), what));
        };
        if (t == kPixelData) {
            if (rows == 0 || columns == 0 || bits == 0)
                throw file.fail("pixel data without rows, columns and bits allocated before them");
            const std::uint64_t needed = rows * columns * std::max(samples, rgb) * (bits / 8);
            if (std::uint64_t(length) < needed)
                throw file.fail("pixel data hold " + std::to_string(length) +
                                " bytes but rows x columns x samples x bits allocated need " + std::to_string(needed));
            pixelDataSeen = true;
        } else if (t == kTransferSyntax) {
            const std::string value = text(64);
            if (value != "1.2.840.10008.1.2" && value != "1.2.840.10008.1.2.1")
                throw file.fail("transfer syntax \"" + value + "\" is not implicit or explicit VR little endian");
            transferSyntaxSeen = true;
        } else if (t == kSeriesUid) {
            seriesUid = text(64);
        } else if (t == kPhotometric) {
            rgb = text(16).starts_with("RGB") ? 3 : 1;
        } else if (t == kRows || t == kColumns || t == kBitsAllocated || t == kSamples) {
            if (length < 2) throw file.fail(what + " holds " + std::to_string(length) + " byte");
            std::uint64_t& field = t == kRows ? rows : t == kColumns ? columns : t == kBitsAllocated ? bits : samples;
            field = file.littleEndian<std::uint16_t>(what);
            // VTK takes a pixel's components from the photometric interpretation ("RGB " 3, else 1), never from
            // the samples per pixel: 0 samples would let the pixel data hold nothing while VTK copies whole rows.
            if (t == kSamples && samples == 0) throw file.fail("samples per pixel " + tagText(t) + " is 0");
            if (t == kBitsAllocated && bits != 8 && bits != 16)
                throw file.fail(std::to_string(bits) + " bits allocated (VTK's DICOM reader reads 8 or 16)");
        }
        file.seek(end, what);
    }
    if (!transferSyntaxSeen) throw file.fail("no transfer syntax (0002,0010)");
    if (!pixelDataSeen) throw file.fail("no pixel data (7FE0,0010)");
    return {{rows, columns, bits, std::max(samples, rgb)}, seriesUid};
}

}  // namespace vr
