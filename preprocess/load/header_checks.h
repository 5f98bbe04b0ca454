// Checks of a file's header made before a VTK reader sees it: VTK's readers trust what headers claim (types, dims,
// data sizes, element lengths) and crash, hang or read uninitialised memory on what fuzzing fed them. Each throws
// InputError naming the file and the problem; a file that passes is one the reader can take safely. They read
// files through a BoundedReader (bounded_reader.h), which no stated length can make read past a file's end.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

namespace vr {

// NIfTI-1 or NIfTI-2 single file (.nii, .nii.gz): size and magic, dims, a scalar datatype with its bitpix, dims
// within memory, and a vox_offset with the data after it inside the file (.nii) or its decompressed stream (.nii.gz).
void checkNiftiHeader(const std::filesystem::path& path);

// NRRD (.nrrd, .nhdr): no control bytes in the header; raw data as long as sizes x type; ASCII data with enough
// values; gzip data that decompress to that length.
void checkNrrdFile(const std::filesystem::path& path);

// OpenVDB (.vdb), versions 222 to 224, walked as OpenVDB 10 reads it: the header, the file's metadata, the grid
// descriptors, each grid's metadata and transform, and every float grid's tree hold no length or count beyond the
// end of the file (OpenVDB allocates, reads or loops over whatever they state), and each tree node's values are the
// size the node holds.
void checkVdbFile(const std::filesystem::path& path);

// VTK XML image data (.vti): a WholeExtent within memory whose first point data array the file can hold (at the
// densest encoding, raw bytes, or at its compressor's largest ratio).
void checkVtkXmlImageFile(const std::filesystem::path& path);

// Legacy VTK structured points (.vtk): the header lines with their numbers, and data as long as POINT_DATA says.
void checkVtkLegacyFile(const std::filesystem::path& path);

// MetaImage (.mha, .mhd): NDims, DimSize, ElementType present and sane; dims within memory; data (in the file or
// the one ElementDataFile) as long as DimSize x ElementType, compressed ones with a CompressedDataSize the file
// holds that decompress to that length.
void checkMetaImageHeader(const std::filesystem::path& path);

// The image layout of one DICOM slice, as VTK's DICOM reader will copy it.
struct DicomSliceLayout {
    std::uint64_t rows, columns, bitsAllocated, samples;
    bool operator==(const DicomSliceLayout&) const = default;
};

// A checked DICOM slice: its layout and the series it belongs to (SeriesInstanceUID (0020,000E); empty where the
// file has none).
struct DicomSlice {
    DicomSliceLayout layout;
    std::string seriesUid;
};

// One DICOM file of a series, walked element by element as VTK's DICOMParser walks it: a DICM magic, explicit or
// implicit VR little-endian transfer syntax, elements inside the file, non-empty values for the elements VTK's
// callbacks parse, 8 or 16 bits allocated, and one pixel data element, after the layout elements, at least rows x
// columns x samples x bits allocated long. Returns that layout and the series UID.
DicomSlice checkDicomFile(const std::filesystem::path& path);

}  // namespace vr
