// Inputs that fuzzing (fuzz/, scripts/fuzz.sh) found mishandled, kept in fuzz/regressions/: every one must be
// refused with an InputError naming the file, not loaded, crashed on or read out of bounds.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

#include "core/errors.h"
#include "preprocess/load/load_volume.h"

// The largest single allocation made through operator new, to tell a loader that checks its input before it
// allocates from one that allocates what a header claims.
std::atomic<std::size_t> largestAllocation{0};

void* operator new(std::size_t bytes) {
    for (std::size_t seen = largestAllocation; bytes > seen && !largestAllocation.compare_exchange_weak(seen, bytes);) {
    }
    if (void* p = std::malloc(bytes ? bytes : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vr {
namespace {
namespace fs = std::filesystem;

const fs::path kRegressions = fs::path(__FILE__).parent_path().parent_path() / "fuzz" / "regressions";

void expectRefused(const fs::path& input) {
    SCOPED_TRACE(input.string());
    ASSERT_TRUE(fs::exists(input));
    try {
        const Volume v = loadVolume(input);
        ADD_FAILURE() << "loaded as " << v.grid.dims.x << "x" << v.grid.dims.y << "x" << v.grid.dims.z
                      << " without an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(input.filename().string()), std::string::npos) << e.what();
    }
}

// A slice whose pixel data element holds fewer bytes than rows x columns x bits allocated: vtkDICOMImageReader
// copies the full slice from it regardless (a heap-buffer-overflow read inside VTK, found by ASan).
TEST(LoadFuzzRegressions, DicomPixelDataShorterThanTheSlice) {
    expectRefused(kRegressions / "dicom" / "short_pixel_data");
}

// vtkNrrdReader reports nothing when raw or ASCII data end early: the missing voxels would be uninitialised memory.
TEST(LoadFuzzRegressions, NrrdDataShorterThanTheSizes) {
    expectRefused(kRegressions / "nrrd" / "raw_data_too_short.nrrd");
    expectRefused(kRegressions / "nrrd" / "ascii_data_too_short.nrrd");
}

// Likewise vtkStructuredPointsReader, ASCII and binary, when POINT_DATA promises more values than the file holds.
TEST(LoadFuzzRegressions, LegacyVtkDataShorterThanThePoints) {
    expectRefused(kRegressions / "vtk_legacy" / "ascii_data_too_short.vtk");
    expectRefused(kRegressions / "vtk_legacy" / "binary_data_too_short.vtk");
}

// A 24-byte .raw.gz whose name claims 512x512x512 uint16 (256 MiB): the loader allocated the claimed size before
// decompressing anything (found with -malloc_limit_mb). Memory must follow the data actually there.
TEST(LoadFuzzRegressions, GzipRawAllocatesOnlyWhatItDecompresses) {
    largestAllocation = 0;
    expectRefused(kRegressions / "raw" / "claims_512x512x512_uint16.raw.gz");
    EXPECT_LT(largestAllocation.load(), std::size_t(64) << 20);
}

// Two active voxels 2^20 apart: densifying their bounding box needs 4 PiB, which the loader asked the allocator for
// without a check (std::bad_alloc, or an ASan abort, instead of an InputError).
TEST(LoadFuzzRegressions, VdbBoundingBoxTooLargeToDensify) {
    expectRefused(kRegressions / "vdb" / "far_apart_voxels.vdb");
}

// Active voxels at x = -2e9 and +2e9: the bounding box's extent overflows int (UBSan: signed overflow in
// openvdb::Coord, called from the loader).
TEST(LoadFuzzRegressions, VdbBoundingBoxBeyondIntRange) {
    expectRefused(kRegressions / "vdb" / "extreme_coordinates.vdb");
}

}  // namespace
}  // namespace vr
