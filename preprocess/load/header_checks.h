// Checks of a file's header made before a VTK reader sees it: VTK's readers trust what headers claim (types, dims,
// data sizes, element lengths) and crash, hang or read uninitialised memory on what fuzzing fed them. Each throws
// InputError naming the file and the problem; a file that passes is one the reader can take safely.
#pragma once
#include <filesystem>

namespace vr {

// NIfTI-1 or NIfTI-2 single file (.nii, .nii.gz): size and magic, dims, a scalar datatype with its bitpix, and a
// vox_offset with the data after it inside the file (.nii).
void checkNiftiHeader(const std::filesystem::path& path);

// NRRD (.nrrd, .nhdr): no control bytes in the header; raw data as long as sizes x type; ASCII data with enough
// values; other encodings but gzip refused.
void checkNrrdFile(const std::filesystem::path& path);

// Legacy VTK structured points (.vtk): the header lines with their numbers, and data as long as POINT_DATA says.
void checkVtkLegacyFile(const std::filesystem::path& path);

// MetaImage (.mha, .mhd): NDims, DimSize, ElementType present and sane; compressed data with CompressedDataSize.
void checkMetaImageHeader(const std::filesystem::path& path);

// One DICOM file of a series: a DICM preamble, explicit or implicit VR little-endian elements that parse, non-empty
// transfer syntax and rescale values, and pixel data at least rows x columns x bits allocated long.
void checkDicomFile(const std::filesystem::path& path);

}  // namespace vr
