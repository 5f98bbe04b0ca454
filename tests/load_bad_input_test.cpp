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
#include <regex>
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
        for (const std::string& w : words)
            EXPECT_NE(message.find(w), std::string::npos) << "no '" << w << "' in: " << message;
    }
}

TEST(LoadBadInput, UnknownExtensionListsTheSupportedFormats) {
    const fs::path path = test::scratchDir("bad_ext") / "volume.xyz";
    writeBytes(path, 64);
    expectInputError(path, {"unknown volume format", ".raw.gz", ".nii.gz", ".mhd", ".vdb", "DICOM"});
}

// The raw options describe headerless raw files; any other format's header says what they would, so giving them
// for one is refused rather than ignored (volprep --spacing 2,2,2 on a NIfTI kept the header's 1 mm).
TEST(LoadBadInput, RawOptionsForAnotherFormatAreRefused) {
    const fs::path nifti = test::datasetsDir() / "colin27_t1_mri.nii.gz";
    RawOptions spacing;
    spacing.spacing = Vec3d{2, 2, 2};
    expectInputError(nifti, {"--spacing", "raw files"}, spacing);
    RawOptions several;
    several.dims = Vec3i{4, 4, 4};
    several.bigEndian = true;
    expectInputError(nifti, {"--dims, --big-endian", "header"}, several);
    const fs::path folder = test::scratchDir("bad_raw_options_folder");
    RawOptions type;
    type.type = ScalarType::Int16;
    expectInputError(folder, {"--type", "DICOM series"}, type);
    // A file of no known format is still told so.
    writeBytes(folder / "volume.xyz", 8);
    expectInputError(folder / "volume.xyz", {"unknown volume format"}, spacing);
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
    expectInputError(dir / "notnrrd.nrrd", {"not a NRRD file"});
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
    expectInputError(dir / "cut.mhd", {"its data hold 1000 bytes", "needs 8192"});
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
    writeText(dir / "garbage.vtk",
              "# vtk DataFile Version 3.0\nnot really\nASCII\nDATASET POLYDATA\nPOINTS 1 float\n0 0 0\n");
    expectInputError(dir / "garbage.vtk", {"garbage.vtk"});
}

// A binary legacy file that ends with its SCALARS line, without a line break: it holds no data at all.
TEST(LoadBadInput, LegacyVtkEndingAtItsScalarsLine) {
    const fs::path path = test::scratchDir("bad_vtk_no_data") / "no_data.vtk";
    writeText(path,
              "# vtk DataFile Version 3.0\nno data\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 3 2\n"
              "SPACING 1 1 1\nORIGIN 0 0 0\nPOINT_DATA 24\nSCALARS s unsigned_char");
    expectInputError(path, {"holds 0 bytes of binary data", "needs 24"});
}

// Gzip (zlib with a gzip header) of `bytes`, or zlib's own format (MetaImage's compressed data).
std::string deflated(const std::string& bytes, bool gzipHeader = true) {
    z_stream z{};
    EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, gzipHeader ? 31 : 15, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&z, uLong(bytes.size())) + 32, '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    z.avail_in = uInt(bytes.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

// A NIfTI-1 header claiming 1024 x 1024 x 256 int16 voxels (512 MiB: within any test machine's memory, so that
// only the data check can refuse it) over `dataBytes` bytes of data.
std::string niftiClaiming512MiB(std::size_t dataBytes) {
    std::string file = niftiFile(1, 3, 16, "n+1", dataBytes);
    const std::int16_t dims[4] = {3, 1024, 1024, 256}, type[2] = {4, 16};  // int16, 16 bits
    std::memcpy(file.data() + 40, dims, sizeof dims);
    std::memcpy(file.data() + 70, type, sizeof type);
    return file;
}

// VTK's readers allocate the image a header claims before they read its data, so a few bytes could make them
// allocate gigabytes. The loaders count what the data really hold first (compressed data by decompressing them up
// to the size needed: gzip's trailer gives the size only mod 2^32, and sizes stated in headers lie as well).
TEST(LoadBadInput, TinyFilesClaimingGigabytesAreRefusedBeforeAllocating) {
    const fs::path dir = test::scratchDir("bad_tiny_claims");
    const auto start = std::chrono::steady_clock::now();
    const std::string header = niftiClaiming512MiB(16);
    writeText(dir / "claims.nii.gz", deflated(header));
    EXPECT_LT(fs::file_size(dir / "claims.nii.gz"), 100u);
    expectInputError(dir / "claims.nii.gz", {"gzip data decompress to 368 bytes", "need 536871264"});
    // A gzip trailer claiming what the header needs is not believed.
    std::string lying = deflated(header);
    const std::uint32_t claimed = 536871264;
    std::memcpy(lying.data() + lying.size() - 4, &claimed, 4);
    writeText(dir / "lying_trailer.nii.gz", lying);
    expectInputError(dir / "lying_trailer.nii.gz", {"corrupt"});
    writeText(dir / "claims.nii", header);
    expectInputError(dir / "claims.nii", {"the file holds 368 bytes", "need 536871264"});

    const std::string nrrd = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1024 1024 256\nencoding: gzip\n\n";
    writeText(dir / "claims.nrrd", nrrd + deflated(std::string(64, '\x03')));
    expectInputError(dir / "claims.nrrd", {"gzip data decompress to 64 bytes", "need 268435456"});

    const std::string mha = "ObjectType = Image\nNDims = 3\nDimSize = 1024 1024 256\nElementType = MET_UCHAR\n";
    const std::string zlibData = deflated(std::string(64, '\x03'), false);
    writeText(dir / "claims_compressed.mha", mha + "CompressedData = True\nCompressedDataSize = " +
                                                 std::to_string(zlibData.size()) + "\nElementDataFile = LOCAL\n" +
                                                 zlibData);
    expectInputError(dir / "claims_compressed.mha", {"compressed data decompress to 64 bytes", "needs 268435456"});
    // metaio allocates CompressedDataSize bytes before reading them.
    writeText(dir / "claims_compressed_size.mha", mha + "CompressedData = True\nCompressedDataSize = 1000000000\n"
                                                        "ElementDataFile = LOCAL\n" + zlibData);
    expectInputError(dir / "claims_compressed_size.mha", {"CompressedDataSize 1000000000 is more than the"});
    writeText(dir / "claims.mha", mha + "ElementDataFile = LOCAL\n" + std::string(64, '\x03'));
    expectInputError(dir / "claims.mha", {"its data hold 64 bytes", "needs 268435456"});
    // VTK XML image data: no encoding packs values denser than raw bytes, no compressor beyond its format's ratio.
    const std::string vti = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" "
                            "byte_order=\"LittleEndian\" header_type=\"UInt32\"COMPRESSOR>\n"
                            " <ImageData WholeExtent=\"0 1023 0 1023 0 255\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
                            "  <Piece Extent=\"0 1023 0 1023 0 255\">\n   <PointData Scalars=\"s\">\n"
                            "    <DataArray type=\"Float32\" Name=\"s\" format=\"appended\" offset=\"0\"/>\n"
                            "   </PointData>\n  </Piece>\n </ImageData>\n <AppendedData encoding=\"raw\">\n  _" +
                            std::string(100, '\x01') + "\n </AppendedData>\n</VTKFile>\n";
    writeText(dir / "claims.vti", std::regex_replace(vti, std::regex("COMPRESSOR"), ""));
    expectInputError(dir / "claims.vti", {"claims 1073741824 bytes of Float32", "(uncompressed)"});
    writeText(dir / "claims_zlib.vti",
              std::regex_replace(vti, std::regex("COMPRESSOR"), " compressor=\"vtkZLibDataCompressor\""));
    expectInputError(dir / "claims_zlib.vti", {"claims 1073741824 bytes", "(vtkZLibDataCompressor)"});
    // Each refused from the few bytes there are (a generous bound, not a benchmark).
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

// What those checks count must accept every honest file: gzip in several members (gzread reads on), zlib data
// written by VTK's MetaImage writer, gzip-encoded NRRD.
TEST(LoadBadInput, HonestCompressedFilesStillLoad) {
    const fs::path dir = test::scratchDir("bad_tiny_claims_honest");
    const std::string file = niftiFile(1, 3, 8, "n+1", 24);
    writeText(dir / "members.nii.gz", deflated(file.substr(0, 100)) + deflated(file.substr(100)));
    EXPECT_EQ(loadVolume(dir / "members.nii.gz").grid.dims, (Vec3i{4, 3, 2}));
    writeText(dir / "plain_named_gz.nii.gz", file);  // no gzip magic: gzread, and VTK, read it as it is
    EXPECT_EQ(loadVolume(dir / "plain_named_gz.nii.gz").grid.dims, (Vec3i{4, 3, 2}));

    writeText(dir / "v.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 10 3 2\nencoding: gzip\n\n" +
                                  deflated(std::string(60, '\x03')));
    EXPECT_EQ(loadVolume(dir / "v.nrrd").grid.dims, (Vec3i{10, 3, 2}));

    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(16, 12, 9);
    image->AllocateScalars(VTK_SHORT, 1);
    auto* values = static_cast<short*>(image->GetScalarPointer());
    for (int i = 0; i < 16 * 12 * 9; ++i) values[i] = short(i * 7 % 1000);
    vtkNew<vtkMetaImageWriter> writer;
    writer->SetFileName((dir / "zipped.mha").c_str());
    writer->SetCompression(true);
    writer->SetInputData(image);
    writer->Write();
    const Volume v = loadVolume(dir / "zipped.mha");
    EXPECT_EQ(v.grid.dims, (Vec3i{16, 12, 9}));
    EXPECT_EQ(v.values[100], 700.0f);
}

}  // namespace
}  // namespace vr
