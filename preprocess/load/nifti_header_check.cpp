// NIfTI header checks before vtkNIFTIImageReader, which trusts the header: an unknown datatype, dim[0] = 0 or a
// file without the magic (read as Analyze 7.5) crash it, and it allocates the image the dims claim before reading.
#include <bit>
#include <cctype>
#include <cstdint>
#include <string>

#include "core/lower_case.h"
#include "preprocess/load/bounded_reader.h"
#include "preprocess/load/compressed_data.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/voxel_budget.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kNifti1Size = 348, kNifti2Size = 540;

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
    BoundedReader file(path, "invalid NIfTI header");
    const std::string name = lowerCase(path.filename().string());
    const bool gzipped = name.ends_with(".gz");
    const std::string header = gzipped ? gzreadBytes(file, kNifti2Size) : file.bytesUpTo(kNifti2Size);
    if (header.size() < kNifti1Size)
        throw file.fail("the file holds " + std::to_string(header.size()) + " bytes, less than a 348-byte header");

    // sizeof_hdr tells the header's byte order.
    const std::int32_t sizeofHdr = valueAt<std::int32_t>(header, 0);
    const std::endian order = sizeofHdr == 348 || sizeofHdr == 540 ? std::endian::little : std::endian::big;
    const std::int32_t size = valueAt<std::int32_t>(header, 0, order);
    if (size != 348 && size != 540)
        throw file.fail("sizeof_hdr is " + std::to_string(sizeofHdr) + ", neither 348 (NIfTI-1) nor 540 (NIfTI-2)");
    const bool nifti2 = size == 540;
    if (nifti2 && header.size() < kNifti2Size)
        throw file.fail("the file holds " + std::to_string(header.size()) +
                        " bytes, less than a 540-byte NIfTI-2 header");

    const std::string magic = nifti2 ? header.substr(4, 4) : header.substr(344, 4);
    const std::string single = nifti2 ? std::string("n+2\0", 4) : std::string("n+1\0", 4);
    const std::string pair = nifti2 ? std::string("ni2\0", 4) : std::string("ni1\0", 4);
    if (magic == pair)
        throw file.fail("the magic says the data lie in a separate .img file; a single .nii file is expected");
    if (magic != single) throw file.fail("no NIfTI magic (\"n+1\" or \"n+2\"); Analyze 7.5 files are not supported");

    std::int64_t dims[8];
    for (int i = 0; i < 8; ++i)
        dims[i] = nifti2 ? valueAt<std::int64_t>(header, 16 + 8 * i, order)
                         : valueAt<std::int16_t>(header, 40 + 2 * i, order);
    if (dims[0] < 1 || dims[0] > 7) throw file.fail("dim[0] is " + std::to_string(dims[0]) + ", not in 1..7");
    double voxels = 1;
    for (int i = 1; i <= dims[0]; ++i) {
        if (dims[i] < 1)
            throw file.fail("dim[" + std::to_string(i) + "] is " + std::to_string(dims[i]) + ", not positive");
        voxels *= double(dims[i]);
    }

    const int datatype = nifti2 ? valueAt<std::int16_t>(header, 12, order) : valueAt<std::int16_t>(header, 70, order);
    const int bitpix = nifti2 ? valueAt<std::int16_t>(header, 14, order) : valueAt<std::int16_t>(header, 72, order);
    const int bits = bitsOf(datatype);
    if (bits == 0) throw file.fail("datatype " + std::to_string(datatype) + " is not a supported scalar type");
    if (bitpix != bits)
        throw file.fail("bitpix is " + std::to_string(bitpix) + " but datatype " + std::to_string(datatype) + " has " +
                        std::to_string(bits) + " bits");

    const double voxOffset =
        nifti2 ? double(valueAt<std::int64_t>(header, 168, order)) : double(valueAt<float>(header, 108, order));
    if (!(voxOffset >= double(size + 4) && voxOffset <= 1e15))
        throw file.fail("vox_offset " + std::to_string(voxOffset) + " does not lie after the header");

    // Dims beyond the third (time, components) give each voxel several values; all must fit in memory before the
    // data are looked for.
    double values = 1;
    for (int i = 4; i <= dims[0]; ++i) values *= double(dims[i]);
    if (values > 1e9) throw file.fail("dims 4 to " + std::to_string(dims[0]) + " claim over 10^9 values per voxel");
    const auto dim = [&](int i) { return i <= dims[0] ? dims[i] : 1; };
    checkVoxelBudget(path, dim(1), dim(2), dim(3), std::size_t(values) * (bits / 8 + sizeof(float)));
    // vtkNIFTIImageReader allocates the image before it reads: the data must be there first. A .nii.gz is counted
    // by decompressing it (up to what is needed), as its gzip trailer gives the size only mod 2^32.
    const std::uintmax_t needed = std::uintmax_t(voxOffset) + std::uintmax_t(voxels) * std::uintmax_t(bits / 8);
    const std::uintmax_t held = gzipped ? decompressedBytes(file, 0, needed, Compression::GzipOrPlain) : file.size();
    if (held < needed)
        throw file.fail(std::string(gzipped ? "the gzip data decompress to " : "the file holds ") +
                        std::to_string(held) + " bytes but vox_offset and dims need " + std::to_string(needed));
}

}  // namespace vr
