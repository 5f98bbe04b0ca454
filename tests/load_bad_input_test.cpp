// Bad input of every kind: each must throw InputError whose message names the file and says what is wrong.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <vtkImageData.h>
#include <vtkMetaImageWriter.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkXMLImageDataWriter.h>
#include <zlib.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

void writeBytes(const fs::path& path, std::size_t n) { writeText(path, std::string(n, '\x07')); }

// Loads `path` expecting an InputError; its message must name the file and contain every one of `words`.
void expectInputError(const fs::path& path, const std::vector<std::string>& words, const RawOptions& raw = {}) {
    try {
        loadVolume(path, raw);
        ADD_FAILURE() << path << " loaded without error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << "message does not name the file: " << message;
        for (const std::string& w : words) EXPECT_NE(message.find(w), std::string::npos) << "no '" << w << "' in: " << message;
    }
}

TEST(LoadBadInput, UnknownExtensionListsTheSupportedFormats) {
    const fs::path path = test::scratchDir("bad_ext") / "volume.xyz";
    writeBytes(path, 64);
    expectInputError(path, {"unknown volume format", ".raw.gz", ".nii.gz", ".mhd", ".vdb", "DICOM"});
}

TEST(LoadBadInput, MissingFile) {
    expectInputError(test::scratchDir("bad_missing") / "nothing_8x8x8_uint8.raw", {"no such file"});
}

TEST(LoadBadInput, RawWithoutDimsOrType) {
    const fs::path dir = test::scratchDir("bad_raw_nodims");
    writeBytes(dir / "plain.raw", 64);
    expectInputError(dir / "plain.raw", {"without dims", "--dims"});
    RawOptions dimsOnly;
    dimsOnly.dims = Vec3i{4, 4, 4};
    expectInputError(dir / "plain.raw", {"without voxel type", "--type"}, dimsOnly);
}

TEST(LoadBadInput, RawSizeMismatchNamesBothSizes) {
    const fs::path dir = test::scratchDir("bad_raw_size");
    writeBytes(dir / "short_4x4x4_uint16.raw", 127);
    expectInputError(dir / "short_4x4x4_uint16.raw", {"127 bytes", "need 128 bytes"});
    writeBytes(dir / "long_4x4x4_uint16.raw", 129);
    expectInputError(dir / "long_4x4x4_uint16.raw", {"129 bytes", "need 128 bytes"});
}

void writeGzip(const fs::path& path, const std::vector<unsigned char>& bytes) {
    gzFile f = gzopen(path.c_str(), "wb");
    gzwrite(f, bytes.data(), unsigned(bytes.size()));
    gzclose(f);
}

TEST(LoadBadInput, GzipRawSizeMismatchNamesBothSizes) {
    const fs::path dir = test::scratchDir("bad_gz_size");
    writeGzip(dir / "short_8x8x8_uint8.raw.gz", std::vector<unsigned char>(500, 3));
    expectInputError(dir / "short_8x8x8_uint8.raw.gz", {"500 bytes", "need 512 bytes"});
    writeGzip(dir / "long_8x8x8_uint8.raw.gz", std::vector<unsigned char>(100000, 3));
    expectInputError(dir / "long_8x8x8_uint8.raw.gz", {"100000 bytes", "need 512 bytes"});
}

TEST(LoadBadInput, TruncatedGzip) {
    const fs::path path = test::scratchDir("bad_gz_truncated") / "cut_32x32x32_uint16.raw.gz";
    std::vector<unsigned char> bytes(32 * 32 * 32 * 2);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>((i * 7919) >> 3);
    writeGzip(path, bytes);
    fs::resize_file(path, fs::file_size(path) / 2);
    expectInputError(path, {"truncated gzip", "65536 bytes"});
}

TEST(LoadBadInput, DimsOverflowing64Bits) {
    const fs::path path = test::scratchDir("bad_overflow") / "huge_2000000000x2000000000x2000000000_float32.raw";
    writeBytes(path, 16);
    expectInputError(path, {"overflow"});
    RawOptions o;
    o.dims = Vec3i{2000000000, 2000000000, 2000000000};
    o.type = ScalarType::UInt8;
    expectInputError(path, {"overflow"}, o);
}

TEST(LoadBadInput, DimsExceedingMemoryFailFast) {
    const fs::path dir = test::scratchDir("bad_memory");
    const auto start = std::chrono::steady_clock::now();
    for (const char* name : {"big_100000x100000x100000_uint8.raw", "big_100000x100000x100000_uint8.raw.gz"}) {
        writeBytes(dir / name, 16);
        expectInputError(dir / name, {"100000x100000x100000", "memory"});
    }
    // Fails before reading or allocating anything (a generous bound, not a benchmark).
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(LoadBadInput, NonPositiveDimsAndSpacing) {
    const fs::path path = test::scratchDir("bad_dims") / "v.raw";
    writeBytes(path, 64);
    RawOptions o;
    o.dims = Vec3i{4, 0, 16};
    o.type = ScalarType::UInt8;
    expectInputError(path, {"positive"}, o);
    o.dims = Vec3i{4, 4, 4};
    o.spacing = Vec3d{1, -1, 1};
    expectInputError(path, {"spacing along y", "positive"}, o);
}

void writeFloats(const fs::path& path, const std::vector<float>& values) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

TEST(LoadBadInput, NanAndInfVoxelsAreCountedAndLocated) {
    const fs::path dir = test::scratchDir("bad_nonfinite");
    std::vector<float> values(4 * 3 * 2, 1.0f);
    values[linearIndex({4, 3, 2}, 1, 2, 1)] = std::numeric_limits<float>::quiet_NaN();
    writeFloats(dir / "nan_4x3x2_float32.raw", values);
    expectInputError(dir / "nan_4x3x2_float32.raw", {"1 voxel is not finite", "(1, 2, 1)"});

    values[linearIndex({4, 3, 2}, 1, 2, 1)] = 0;
    values[linearIndex({4, 3, 2}, 3, 0, 0)] = std::numeric_limits<float>::infinity();
    values[linearIndex({4, 3, 2}, 2, 1, 1)] = -std::numeric_limits<float>::infinity();
    writeFloats(dir / "inf_4x3x2_float32.raw", values);
    expectInputError(dir / "inf_4x3x2_float32.raw", {"2 voxels are not finite", "(3, 0, 0)"});
}

TEST(LoadBadInput, MalformedNrrdHeader) {
    const fs::path dir = test::scratchDir("bad_nrrd");
    writeText(dir / "notnrrd.nrrd", "P5\n12 4\n255\n" + std::string(48, 'x'));
    expectInputError(dir / "notnrrd.nrrd", {"not a nrrd file"});
    writeText(dir / "badtype.nrrd", "NRRD0004\ntype: quaternion\ndimension: 3\nsizes: 12 4 3\nencoding: raw\n\n" +
                                         std::string(144, 'x'));
    expectInputError(dir / "badtype.nrrd", {"quaternion"});
    writeText(dir / "vector.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 40 30\nencoding: raw\n\n" +
                                       std::string(3600, 'x'));
    expectInputError(dir / "vector.nrrd", {"components"});
}

// Headers are checked before the reader allocates: a size no machine holds fails at once.
TEST(LoadBadInput, HeadersClaimingTooManyVoxels) {
    const fs::path dir = test::scratchDir("bad_header_size");
    writeText(dir / "huge.nrrd", "NRRD0004\ntype: float\ndimension: 3\nsizes: 100000 100000 100000\n"
                                 "encoding: raw\nendian: little\n\n" + std::string(64, 'x'));
    expectInputError(dir / "huge.nrrd", {"100000x100000x100000", "memory"});
    writeText(dir / "huge.vtk", "# vtk DataFile Version 3.0\nhuge\nBINARY\nDATASET STRUCTURED_POINTS\n"
                                "DIMENSIONS 2000000000 2000000000 2000000000\nSPACING 1 1 1\nORIGIN 0 0 0\n"
                                "POINT_DATA 8\nSCALARS s unsigned_char\nLOOKUP_TABLE default\n" + std::string(8, 'x'));
    expectInputError(dir / "huge.vtk", {"2000000000x2000000000x2000000000"});

    openvdb::initialize();
    auto sparse = openvdb::FloatGrid::create(0.0f);  // two voxels whose bounding box is 2^30 wide on every axis
    sparse->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    sparse->tree().setValue(openvdb::Coord(1 << 30, 1 << 30, 1 << 30), 1.0f);
    {
        openvdb::io::File file((dir / "sparse.vdb").string());
        file.write({sparse});
    }
    expectInputError(dir / "sparse.vdb", {"1073741825x1073741825x1073741825"});
}

TEST(LoadBadInput, ZeroSpacingInAHeader) {
    const fs::path path = test::scratchDir("bad_spacing") / "flat.vti";
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(4, 4, 4);
    image->SetSpacing(1, 0, 1);
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(image);
    writer->Write();
    expectInputError(path, {"spacing along y", "positive"});
}

TEST(LoadBadInput, TruncatedMetaImageData) {
    const fs::path dir = test::scratchDir("bad_mhd");
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(16, 16, 16);
    image->AllocateScalars(VTK_SHORT, 1);
    vtkNew<vtkMetaImageWriter> writer;
    writer->SetFileName((dir / "cut.mhd").c_str());
    writer->SetRAWFileName((dir / "cut.raw").c_str());
    writer->SetCompression(false);
    writer->SetInputData(image);
    writer->Write();
    fs::resize_file(dir / "cut.raw", 1000);
    expectInputError(dir / "cut.mhd", {"cannot read MetaImage", "not read completely", "8192", "1000"});
    fs::remove(dir / "cut.raw");
    expectInputError(dir / "cut.mhd", {"cannot read MetaImage", "Cannot open data file"});
}

TEST(LoadBadInput, CorruptNiftiHeader) {
    const fs::path dir = test::scratchDir("bad_nifti");
    std::string header(352, '\0');
    header[0] = 'Z';  // sizeof_hdr must be 348 (or 540 for NIfTI-2)
    writeText(dir / "corrupt.nii", header + std::string(64, 'x'));
    expectInputError(dir / "corrupt.nii", {"corrupt.nii"});
    writeText(dir / "text.nii.gz", "this is not gzip, nor NIfTI");
    expectInputError(dir / "text.nii.gz", {"text.nii.gz"});
}

// vtkNIFTIImageReader crashes on headers it trusts, so the loader checks them first: a valid 4x3x2 uint8 file (it
// must load, in both NIfTI versions) and variants each broken in one field.
std::string niftiFile(int version, std::int16_t dim0, std::int16_t bitpix, const char* magic, std::size_t dataBytes) {
    const bool two = version == 2;
    std::string file(two ? 544 : 352, '\0');
    const auto put = [&](std::size_t at, auto value) { std::memcpy(file.data() + at, &value, sizeof value); };
    put(0, std::int32_t(two ? 540 : 348));
    const std::int64_t dims[8] = {dim0, 4, 3, 2, 1, 1, 1, 1};
    for (int i = 0; i < 8; ++i) two ? put(16 + 8 * i, dims[i]) : put(40 + 2 * i, std::int16_t(dims[i]));
    put(two ? 12 : 70, std::int16_t(2));  // uint8
    put(two ? 14 : 72, bitpix);
    for (int i = 1; i < 4; ++i) two ? put(104 + 8 * i, 1.0) : put(76 + 4 * i, 1.0f);  // pixdim
    two ? put(168, std::int64_t(544)) : put(108, 352.0f);                           // vox_offset
    std::memcpy(file.data() + (two ? 4 : 344), magic, two ? 8 : 4);
    return file + std::string(dataBytes, '\x05');
}

TEST(LoadBadInput, NiftiHeaderCheckedBeforeVtkReadsIt) {
    const fs::path dir = test::scratchDir("bad_nifti_fields");
    writeText(dir / "good1.nii", niftiFile(1, 3, 8, "n+1", 24));
    EXPECT_EQ(loadVolume(dir / "good1.nii").grid.dims, (Vec3i{4, 3, 2}));
    writeText(dir / "good2.nii", niftiFile(2, 3, 8, "n+2\0\r\n\032\n", 24));
    EXPECT_EQ(loadVolume(dir / "good2.nii").grid.dims, (Vec3i{4, 3, 2}));
    writeText(dir / "dim0.nii", niftiFile(1, 0, 8, "n+1", 24));
    expectInputError(dir / "dim0.nii", {"dim[0] is 0"});
    writeText(dir / "bitpix.nii", niftiFile(1, 3, 16, "n+1", 24));
    expectInputError(dir / "bitpix.nii", {"bitpix is 16"});
    writeText(dir / "pair.nii", niftiFile(1, 3, 8, "ni1", 24));
    expectInputError(dir / "pair.nii", {".img"});
    writeText(dir / "short.nii", niftiFile(1, 3, 8, "n+1", 20));
    expectInputError(dir / "short.nii", {"372 bytes", "376"});
}

TEST(LoadBadInput, VdbThatIsNotAVdb) {
    const fs::path dir = test::scratchDir("bad_vdb");
    writeText(dir / "text.vdb", "not an OpenVDB file at all, just some text that is long enough to be read");
    expectInputError(dir / "text.vdb", {"not a readable OpenVDB file"});
}

TEST(LoadBadInput, VdbWithoutFloatGridOrEmpty) {
    openvdb::initialize();
    const fs::path dir = test::scratchDir("bad_vdb_grids");
    auto ints = openvdb::Int32Grid::create(0);
    ints->tree().setValue(openvdb::Coord(1, 2, 3), 5);
    {
        openvdb::io::File file((dir / "ints.vdb").string());
        file.write({ints});
    }
    expectInputError(dir / "ints.vdb", {"no float grid"});
    auto empty = openvdb::FloatGrid::create(0.0f);
    empty->setName("nothing");
    {
        openvdb::io::File file((dir / "empty.vdb").string());
        file.write({empty});
    }
    expectInputError(dir / "empty.vdb", {"empty"});
}

TEST(LoadBadInput, FolderWithoutDicomFiles) {
    const fs::path dir = test::scratchDir("bad_dicom");
    fs::create_directories(dir / "empty");
    expectInputError(dir / "empty", {"no DICOM files"});
    fs::create_directories(dir / "text");
    writeText(dir / "text" / "readme.txt", "no DICOM here\n");
    writeBytes(dir / "text" / "slice.dcm", 300);
    expectInputError(dir / "text", {"no DICOM files", "2 files"});
}

TEST(LoadBadInput, GarbageVtkFiles) {
    const fs::path dir = test::scratchDir("bad_vtk");
    writeText(dir / "garbage.vti", "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\"><ImageData WholeExtent=");
    expectInputError(dir / "garbage.vti", {"garbage.vti"});
    writeText(dir / "binary.vti", std::string(200, '\x01'));
    expectInputError(dir / "binary.vti", {"binary.vti"});
    writeText(dir / "garbage.vtk", "# vtk DataFile Version 3.0\nnot really\nASCII\nDATASET POLYDATA\nPOINTS 1 float\n0 0 0\n");
    expectInputError(dir / "garbage.vtk", {"garbage.vtk"});
}

}  // namespace
}  // namespace vr
