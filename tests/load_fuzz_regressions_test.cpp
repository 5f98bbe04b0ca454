// Inputs that fuzzing (fuzz/, scripts/fuzz.sh) found mishandled, kept in fuzz/regressions/: every one must be
// refused with an InputError naming the file, not loaded, crashed on, hung on or read out of bounds.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"

// The largest single allocation made through operator new and new[], to tell a loader that checks its input before
// it allocates from one that allocates whatever a header claims. An allocation that cannot be served throws
// std::bad_alloc, as in an ordinary build, also under ASan (whose own operator new aborts instead; see
// __asan_default_options below), so that a loader's handling of it is what is tested.
std::atomic<std::size_t> largestAllocation{0};

extern "C" const char* __asan_default_options() { return "allocator_may_return_null=1:alloc_dealloc_mismatch=0"; }

void* operator new(std::size_t bytes) {
    void* p = std::malloc(bytes ? bytes : 1);
    if (!p) throw std::bad_alloc();  // a request that failed allocated nothing: not counted
    for (std::size_t seen = largestAllocation; bytes > seen && !largestAllocation.compare_exchange_weak(seen, bytes);) {
    }
    return p;
}
void* operator new[](std::size_t bytes) { return operator new(bytes); }
// GCC takes these frees, inlined where operator new was too, for mismatched: they match the malloc above.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace vr {
namespace {
namespace fs = std::filesystem;

// __FILE__ is relative to the build folder, where the compiler runs, when ccache's base_dir rewrites it.
const fs::path kThisFile = fs::path(__FILE__).is_absolute() ? fs::path(__FILE__) : fs::path(VR_BINARY_DIR) / __FILE__;
const fs::path kRegressionsFolder = kThisFile.parent_path().parent_path() / "fuzz" / "regressions";

// Run in a child process: exits 0 only when loadVolume throws an InputError naming the file (and holding `problem`,
// where given), having allocated at most maxAllocation bytes at once. The alarm turns a hang into a failure instead
// of a stalled suite.
[[noreturn]] void loadExpectingRefusal(const fs::path& input, std::size_t maxAllocation, const char* problem) {
    alarm(20);
    largestAllocation = 0;
    try {
        const Volume v = loadVolume(input);
        std::fprintf(stderr, "loaded as %dx%dx%d without an error\n", v.grid.dims.x, v.grid.dims.y, v.grid.dims.z);
    } catch (const InputError& e) {
        if (std::string(e.what()).find(input.filename().string()) == std::string::npos)
            std::fprintf(stderr, "the message does not name the file: %s\n", e.what());
        else if (problem && std::string(e.what()).find(problem) == std::string::npos)
            std::fprintf(stderr, "the message does not say \"%s\": %s\n", problem, e.what());
        else if (largestAllocation > maxAllocation)
            std::fprintf(stderr, "refused, but only after allocating %zu bytes at once\n", largestAllocation.load());
        else
            std::_Exit(0);
    }
    std::_Exit(1);
}

// What refusing a small file may allocate at once (the readers' own buffers): far below what its header claims.
constexpr std::size_t kSmallInputAllocation = std::size_t(64) << 20;
// No bound that matters: the input's bug was not an allocation.
constexpr std::size_t kAnyAllocation = std::size_t(1) << 40;

// In a child process, so that a crash or a hang fails this test alone.
void expectRefused(const fs::path& input, std::size_t maxAllocation, const char* problem) {
    ASSERT_TRUE(fs::exists(input)) << input;
    GTEST_FLAG_SET(death_test_style, "threadsafe");  // TBB and VTK may have started threads
    EXPECT_EXIT(loadExpectingRefusal(input, maxAllocation, problem), testing::ExitedWithCode(0), "") << input;
}

// One kind of input fuzzing found mishandled: the files or DICOM series folders (under fuzz/regressions/) that show
// it, how much refusing one may allocate at once, and (where given) a fragment of the message refusing each.
struct Regression {
    const char* name;
    std::vector<const char*> inputs;
    std::size_t maxAllocation = kAnyAllocation;
    const char* problem = nullptr;
};

const Regression kRegressions[] = {
    // A slice whose pixel data element holds fewer bytes than rows x columns x bits allocated: vtkDICOMImageReader
    // copies the full slice from it regardless (heap-buffer-overflow read inside VTK, found by ASan).
    {"DicomPixelDataShorterThanTheSlice", {"dicom/short_pixel_data"}},
    // Zero-length values of elements that VTK's DICOMAppHelper parses in a callback: it passes the null value pointer
    // to strcmp (TransferSyntaxUID, 0002,0010) or strtod (RescaleSlope, 0028,1053): SEGV inside VTK.
    {"DicomEmptyElementValues", {"dicom/empty_transfer_syntax", "dicom/empty_rescale_slope"}},
    // VTK's DICOMParser reads on past the pixel data to the end of the file: an empty Columns there reaches its
    // callback as null (SEGV, found by CI's fuzzing), an empty SeriesInstanceUID becomes std::string(nullptr).
    {"DicomEmptyElementsAfterThePixelData",
     {"dicom/columns_empty_after_pixel_data", "dicom/empty_series_uid_after_pixel_data"}},
    // vtkDICOMImageReader sizes the volume from one slice and copies each slice whole into it: a later, larger slice
    // overflowed it (SEGV).
    {"DicomSlicesOfDifferentSizes", {"dicom/slices_of_different_sizes"}},
    // Samples per pixel (0028,0002) of 0 and no photometric interpretation: the check required rows x columns x 0
    // x bits allocated bytes of pixel data, but VTK, which counts one component whatever the samples say, copied
    // whole rows (3 of 8191 16-bit pixels) from the 24 bytes there (heap-buffer-overflow read in vtkDICOMImageReader::
    // ExecuteDataWithInformation, found by fuzz_dicom). The folder is the series fuzz_dicom made of the input.
    {"DicomZeroSamplesPerPixel", {"dicom/zero_samples_per_pixel"}, kAnyAllocation,
     "samples per pixel (0028,0002) is 0"},
    // vtkNrrdReader reports nothing when raw or ASCII data end early: the missing voxels would be uninitialised memory.
    {"NrrdDataShorterThanTheSizes", {"nrrd/raw_data_too_short.nrrd", "nrrd/ascii_data_too_short.nrrd"}},
    // NUL bytes inside a "space directions" vector send vtkNrrdReader::ReadHeader into an endless loop.
    {"NrrdHeaderWithNulBytes", {"nrrd/nul_in_space_directions.nrrd"}},
    // vtkNrrdReader reads through a null stream (SEGV inside VTK) when the dimension field is missing, comes after the
    // sizes (found by fuzz_nrrd), or leaves it fewer than 2 image axes once it takes the first axis for components; and
    // when the sizes are missing because their key has a trailing space ("sizes : ...", which VTK does not take for
    // "sizes": found by fuzz_nrrd).
    {"NrrdHeadersVtkReadsThroughANullStream",
     {"nrrd/no_dimension_field.nrrd", "nrrd/sizes_before_dimension.nrrd", "nrrd/one_image_axis.nrrd",
      "nrrd/sizes_key_with_a_trailing_space.nrrd"}},
    // " type: " (a key after a space, which vtkNrrdReader does not take for "type") sends vtkNrrdReader::ReadHeader
    // into an endless loop (found by fuzz_nrrd): keys are matched as VTK matches them, and a header without a type is
    // refused.
    {"NrrdKeyAfterASpace", {"nrrd/type_key_after_a_space.nrrd"}},
    // A data file field with no value: vtkNrrdReader compares the first word of it, which is not there (SEGV, found
    // by fuzz_nrrd).
    {"NrrdEmptyDataFileField", {"nrrd/empty_data_file_field.nrrd"}, kAnyAllocation, "names no file"},
    // The same before a type vtkNrrdReader does not know: its header parse reaches the data file field first (SEGV,
    // found by fuzz_nrrd), so that field is checked whatever the type.
    {"NrrdEmptyDataFileFieldBeforeAnUnknownType", {"nrrd/empty_data_file_field_before_an_unknown_type.nrrd"},
     kAnyAllocation, "names no file"},
    // A data file field of 4 words or more is a file pattern "FORMAT MIN MAX STEP" to vtkNrrdReader, which steps by
    // atoi of the words: by 0 it inserted file names until memory ran out, 22 such inputs in 20 minutes of fuzz_nrrd
    // (its snprintf of the format would also take any conversion). "LIST" names the files on the lines after it; two
    // data file fields give two files. Data in several files is refused.
    {"NrrdDataInSeveralFiles",
     {"nrrd/data_file_pattern_stepping_by_zero.nrrd", "nrrd/data_file_pattern_with_a_format_of_garbage.nrrd",
      "nrrd/data_files_listed.nrrd"},
     kSmallInputAllocation, "several files"},
    {"NrrdTwoDataFileFields", {"nrrd/two_data_file_fields.nrrd"}, kSmallInputAllocation, "both"},
    // sizes "10+0 3 22222220" with dimension 4: read as 10, +0, 3 and 22222220 the header check left the 0 to VTK's
    // reader, which read 10, 3 and 22222220 and allocated 2.7 GB for an ASCII file of a few bytes (found by
    // fuzz_nrrd). A size token is an integer and nothing else.
    {"NrrdSizeTokenWithAPlus", {"nrrd/size_token_with_a_plus.nrrd"}, kSmallInputAllocation, "sizes"},
    // "encoding: ascIi": vtkNrrdReader reads it as ASCII, in any case, and allocated what the sizes claim (2.2 GB)
    // before it found 3 values; the check, matching "ascii" alone, had left it to the reader (found by fuzz_nrrd).
    {"NrrdEncodingInMixedCase", {"nrrd/encoding_in_mixed_case.nrrd"}, kSmallInputAllocation, "ASCII values"},
    // A header without a blank line whose last line has no line break: vtkNrrdReader rereads that line forever
    // (std::getline keeps it once the stream has ended). Found by CI's fuzzing (timeouts).
    {"NrrdLastHeaderLineWithoutALineBreak",
     {"nrrd/last_header_line_without_line_break.nrrd", "nrrd/unknown_type_last_line_without_line_break.nrrd"}},
    // Likewise vtkStructuredPointsReader, ASCII and binary, when POINT_DATA promises more values than the file holds.
    {"LegacyVtkDataShorterThanThePoints",
     {"vtk_legacy/ascii_data_too_short.vtk", "vtk_legacy/binary_data_too_short.vtk"}},
    // Garbage after ORIGIN in a binary legacy file (a "field" keyword and binary bytes): vtkStructuredPointsReader::
    // ReadMeshSimple dereferences a null pointer (SEGV inside VTK).
    {"LegacyVtkGarbageAfterOrigin", {"vtk_legacy/garbled_after_origin.vtk"}},
    // vtkNIFTIImageReader trusts the header: an unknown datatype code (1279) crashes RequestInformation (SIGBUS); zero
    // dims (dim[0] = 0) divide by zero in RequestData (SIGFPE); headers without the NIfTI magic, read as Analyze 7.5
    // with garbage datatype/bitpix/dims, crash RequestData (SEGV). The loader must validate the header (sizeof_hdr,
    // magic, dim[0] in 1..7, positive dims, a known datatype with its bitpix, vox_offset) before VTK reads it.
    {"NiftiHeadersVtkCrashesOn",
     {"nifti/unknown_datatype.nii", "nifti/fpe_zero_dims.nii", "nifti/segv_in_request_data.nii",
      "nifti/segv_in_request_data.nii.gz"}},
    // Headers claiming 10^13 voxels or more over a few bytes of data: VTK's readers allocate the claimed image before
    // reading it, and the std::bad_alloc ends in std::terminate (an ASan abort under the sanitizers). The loaders must
    // check the header's extent (UpdateInformation) against the memory budget before Update().
    {"HeaderDimsBeyondMemory",
     {"metaimage/absurd_dims.mha", "nrrd/absurd_sizes.nrrd", "nifti/absurd_dims.nii", "vti/absurd_extent.vti"}},
    // Compressed MetaImage data without a usable CompressedDataSize (a garbled header found by fuzz_metaimage):
    // metaio's M_ReadElements calls new[] with (size_t)-1, so std::bad_alloc escapes VTK (an ASan abort under the
    // sanitizers).
    {"MetaImageCompressedWithoutSize", {"metaimage/compressed_unknown_size.mha"}},
    // More garbled compressed headers from fuzz_metaimage that made metaio call new[] with (size_t)-1: a CompressedData
    // value metaio takes for true ("Tr/e": it looks at the first letter) without a CompressedDataSize, and compressed
    // data with an empty ElementDataFile. And a garbled file pattern ("LOCA%N..."), with which metaio overruns a heap
    // buffer (strlen in MetaImage::ReadStream); lists and patterns of data files are refused.
    {"MetaImageGarbledCompressionAndDataFile",
     {"metaimage/compressed_flag_spelled_tr_e.mha", "metaimage/compressed_empty_data_file.mha",
      "metaimage/garbled_data_file_pattern.mha"}},
    // A 24-byte .raw.gz whose name claims 512x512x512 uint16 (256 MiB): the loader allocated the claimed size before
    // decompressing anything (found with -malloc_limit_mb). Memory must follow the data actually there.
    {"GzipRawAllocatesOnlyWhatItDecompresses", {"raw/claims_512x512x512_uint16.raw.gz"}, kSmallInputAllocation},
    // A plain .raw of 35 bytes whose name claims 600x600x600 uint8: the loader allocated the claimed volume's floats
    // (864 MB) before it compared the file's size with its dims (found by fuzz_raw, with dims of gigabytes).
    {"PlainRawAllocatesNothingBeforeItsSizeIsChecked", {"raw/claims_600x600x600_uint8.raw"}, kSmallInputAllocation,
     "bytes of voxel data"},
    // Two active voxels 2^20 apart: densifying their bounding box needs 4 PiB, which the loader asked the allocator for
    // without a check (std::bad_alloc, or an ASan abort, instead of an InputError).
    {"VdbBoundingBoxTooLargeToDensify", {"vdb/far_apart_voxels.vdb"}},
    // Active voxels at x = -2e9 and +2e9: the bounding box's extent overflows int (UBSan: signed overflow in
    // openvdb::Coord::operator-, called from the loader). And active voxels at x = 1845493824 (found by fuzz_vdb):
    // copyToDense splits the box at (min + max) / 2, which overflows int (UBSan, in openvdb::CoordBBox's splitting
    // constructor).
    {"VdbBoundingBoxBeyondIntRange", {"vdb/extreme_coordinates.vdb", "vdb/active_box_near_int_max.vdb"}},
    // Length-prefixed strings and metadata values of up to 4 GiB in a file of a few KiB (found by fuzz_vdb): OpenVDB
    // allocates, and zero-fills, what they state (GridDescriptor::read, MetaMap::readMeta, Transform::read,
    // DelayedLoadMetadata::readValue), and a grid ending beyond the file let it read a zipped block's length of
    // 0x3030300000000 bytes. The loader walks these before OpenVDB reads them. The last input: delayed-load arrays
    // longer than their metadata's stated size: OpenVDB reads on past it, and the next metadata name's length (1.8 GiB)
    // came from the middle of the arrays.
    {"VdbLengthsBeyondTheFile",
     {"vdb/grid_name_of_4gib.vdb", "vdb/instance_parent_name_of_4gib.vdb", "vdb/metadata_value_of_4gib.vdb",
      "vdb/grid_metadata_of_1gib.vdb", "vdb/zipped_length_beyond_the_file.vdb", "vdb/transform_type_of_4gib.vdb",
      "vdb/delayed_load_count_of_4g.vdb", "vdb/delayed_load_longer_than_stated.vdb"}, kSmallInputAllocation},
    // An int32 grid whose zipped values overflow a heap buffer inside OpenVDB (io::unzipFromStream, found by fuzz_vdb):
    // the loader reads only the metadata of grids that are not float grids, never their trees.
    {"VdbTreesOfOtherGridsAreNotRead", {"vdb/int_tree_overflowing_unzip.vdb"}},
    // Float grids' trees that OpenVDB 10 mishandles (found by fuzz_vdb, but for the one written by hand): a root tile
    // count of 1.7 billion it loops over for minutes in a file of 6 KiB, raw values longer than the node that it reads
    // into the node's buffer (a heap overflow in io::unzipFromStream, via readCompressedValues), and zipped lengths of
    // 8 GiB and 0x7469736e65640000 bytes it allocates. The loader walks the float trees before OpenVDB reads them.
    {"VdbFloatTreesOpenVdbMishandles",
     {"vdb/float_tree_read_for_a_minute.vdb", "vdb/float_tree_overflowing_unzip.vdb",
      "vdb/float_tree_raw_values_beyond_the_node.vdb", "vdb/float_tree_zipped_length_of_8gib.vdb",
      "vdb/absurd_length_field.vdb"}, kSmallInputAllocation},
    // Active tiles in a float tree of 13 KiB whose bounding box densifies to 6 GiB (found by fuzz_vdb): within this
    // machine's memory, but not backed by the file (preprocess/load/vdb/vdb_loader.cpp: at most 256 voxels per byte).
    {"VdbSparseGridDensifyingToGigabytes", {"vdb/float_tree_active_box_of_6gib.vdb"}, kSmallInputAllocation},
};

// Test names show the regression's name, not its bytes.
void PrintTo(const Regression& r, std::ostream* os) { *os << r.name; }

class LoadFuzzRegressions : public testing::TestWithParam<Regression> {};

// Every input of the kind is refused, each in a child process.
TEST_P(LoadFuzzRegressions, AreRefused) {
    ASSERT_FALSE(GetParam().inputs.empty());
    for (const char* input : GetParam().inputs)
        expectRefused(kRegressionsFolder / input, GetParam().maxAllocation, GetParam().problem);
}

INSTANTIATE_TEST_SUITE_P(, LoadFuzzRegressions, testing::ValuesIn(kRegressions),
                         [](const testing::TestParamInfo<Regression>& info) { return std::string(info.param.name); });

// Every file kept in fuzz/regressions/ is an input listed above, or lies in a listed folder: an input only kept there
// would be tested by nothing.
TEST(LoadFuzzRegressionsFolder, HoldsOnlyListedInputs) {
    std::set<std::string> listed;
    for (const Regression& r : kRegressions) listed.insert(r.inputs.begin(), r.inputs.end());
    int files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(kRegressionsFolder)) {
        if (!entry.is_regular_file()) continue;
        ++files;
        const fs::path relative = fs::relative(entry.path(), kRegressionsFolder);
        bool covered = false;
        for (fs::path p = relative; !p.empty() && !covered; p = p.parent_path()) covered = listed.contains(p.string());
        EXPECT_TRUE(covered) << relative << " is in no Regression of kRegressions";
    }
    EXPECT_GE(files, int(listed.size())) << "fewer files than listed inputs in " << kRegressionsFolder;
}

}  // namespace
}  // namespace vr
