// NIfTI header checks before vtkNIFTIImageReader, which trusts the header: an unknown datatype, dim[0] = 0 or a
// file without the magic (read as Analyze 7.5) crash it, and it allocates the image the dims claim before reading.
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kNifti1Size = 348, kNifti2Size = 540;

// Up to kNifti2Size bytes from the start of the file, decompressed for .nii.gz.
std::string headerBytes(const fs::path& path, bool gzipped) {
    std::string bytes(kNifti2Size, '\0');
    std::size_t got = 0;
    if (gzipped) {
        gzFile file = gzopen(path.c_str(), "rb");
        if (!file) throw fileError(path.string(), "cannot open");
        const int n = gzread(file, bytes.data(), unsigned(bytes.size()));
        gzclose(file);
        if (n < 0) throw fileError(path.string(), "corrupt gzip data in the NIfTI header");
        got = std::size_t(n);
    } else {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw fileError(path.string(), "cannot open");
        in.read(bytes.data(), std::streamsize(bytes.size()));
        got = std::size_t(in.gcount());
    }
    bytes.resize(got);
    return bytes;
}

// Reads a little- or big-endian field at `offset` (the header's byte order is told by sizeof_hdr).
template <typename T>
T field(const std::string& header, std::size_t offset, bool swap) {
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), header.data() + offset, sizeof(T));
    if (swap) std::reverse(raw.begin(), raw.end());
    return std::bit_cast<T>(raw);
}

// The scalar datatypes VTK reads, with the bitpix each must come with.
int bitsOf(int datatype) {
    switch (datatype) {
        case 2:
        case 256: return 8;  // uint8, int8
        case 4:
        case 512: return 16;  // int16, uint16
        case 8:
        case 16:
        case 768: return 32;  // int32, float32, uint32
        case 64:
        case 1024:
        case 1280: return 64;  // float64, int64, uint64
        default: return 0;
    }
}

}  // namespace

void checkNiftiHeader(const fs::path& path) {
    std::string name = path.filename().string();
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool gzipped = name.ends_with(".gz");
    const std::string header = headerBytes(path, gzipped);
    const auto fail = [&](const std::string& problem) {
        return fileError(path.string(), "invalid NIfTI header: " + problem);
    };
    if (header.size() < kNifti1Size)
        throw fail("the file holds " + std::to_string(header.size()) + " bytes, less than a 348-byte header");

    const std::int32_t sizeofHdr = field<std::int32_t>(header, 0, false);
    const std::int32_t swapped = field<std::int32_t>(header, 0, true);
    const bool swap = sizeofHdr != 348 && sizeofHdr != 540;
    const std::int32_t size = swap ? swapped : sizeofHdr;
    if (size != 348 && size != 540)
        throw fail("sizeof_hdr is " + std::to_string(sizeofHdr) + ", neither 348 (NIfTI-1) nor 540 (NIfTI-2)");
    const bool nifti2 = size == 540;
    if (nifti2 && header.size() < kNifti2Size)
        throw fail("the file holds " + std::to_string(header.size()) + " bytes, less than a 540-byte NIfTI-2 header");

    const std::string magic = nifti2 ? header.substr(4, 4) : header.substr(344, 4);
    const std::string single = nifti2 ? std::string("n+2\0", 4) : std::string("n+1\0", 4);
    const std::string pair = nifti2 ? std::string("ni2\0", 4) : std::string("ni1\0", 4);
    if (magic == pair)
        throw fail("the magic says the data lie in a separate .img file; a single .nii file is expected");
    if (magic != single) throw fail("no NIfTI magic (\"n+1\" or \"n+2\"); Analyze 7.5 files are not supported");

    std::int64_t dims[8];
    for (int i = 0; i < 8; ++i)
        dims[i] =
            nifti2 ? field<std::int64_t>(header, 16 + 8 * i, swap) : field<std::int16_t>(header, 40 + 2 * i, swap);
    if (dims[0] < 1 || dims[0] > 7) throw fail("dim[0] is " + std::to_string(dims[0]) + ", not in 1..7");
    double voxels = 1;
    for (int i = 1; i <= dims[0]; ++i) {
        if (dims[i] < 1) throw fail("dim[" + std::to_string(i) + "] is " + std::to_string(dims[i]) + ", not positive");
        voxels *= double(dims[i]);
    }

    const int datatype = nifti2 ? field<std::int16_t>(header, 12, swap) : field<std::int16_t>(header, 70, swap);
    const int bitpix = nifti2 ? field<std::int16_t>(header, 14, swap) : field<std::int16_t>(header, 72, swap);
    const int bits = bitsOf(datatype);
    if (bits == 0) throw fail("datatype " + std::to_string(datatype) + " is not a supported scalar type");
    if (bitpix != bits)
        throw fail("bitpix is " + std::to_string(bitpix) + " but datatype " + std::to_string(datatype) + " has " +
                   std::to_string(bits) + " bits");

    const double voxOffset =
        nifti2 ? double(field<std::int64_t>(header, 168, swap)) : double(field<float>(header, 108, swap));
    if (!(voxOffset >= double(size + 4) && voxOffset <= 1e15))
        throw fail("vox_offset " + std::to_string(voxOffset) + " does not lie after the header");

    // Dims beyond the third (time, components) give each voxel several values; all must fit in memory before the
    // data are looked for.
    double values = 1;
    for (int i = 4; i <= dims[0]; ++i) values *= double(dims[i]);
    if (values > 1e9) throw fail("dims 4 to " + std::to_string(dims[0]) + " claim over 10^9 values per voxel");
    const auto dim = [&](int i) { return i <= dims[0] ? dims[i] : 1; };
    checkVoxelBudget(path, dim(1), dim(2), dim(3), std::size_t(values) * (bits / 8 + sizeof(float)));
    // vtkNIFTIImageReader allocates the image before it reads: the data must be there first. A .nii.gz is counted
    // by decompressing it (up to what is needed), as its gzip trailer gives the size only mod 2^32.
    const std::uintmax_t needed = std::uintmax_t(voxOffset) + std::uintmax_t(voxels) * std::uintmax_t(bits / 8);
    std::error_code ec;
    const std::uintmax_t held =
        gzipped ? decompressedBytes(path, 0, needed, Compression::GzipOrPlain) : fs::file_size(path, ec);
    if (ec) throw fileError(path.string(), "cannot read: " + ec.message());
    if (held < needed)
        throw fail(std::string(gzipped ? "the gzip data decompress to " : "the file holds ") + std::to_string(held) +
                   " bytes but vox_offset and dims need " + std::to_string(needed));
}

}  // namespace vr
