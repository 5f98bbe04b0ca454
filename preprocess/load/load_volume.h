// Loading any supported volume file into a vr::Volume (dispatch on the file name / folder).
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "core/volume.h"

namespace vr {

// Flags for headerless raw files; dims/type may also be parsed from names like engine_256x256x128_uint8.raw[.gz]
// (flags win over the name). Spacing defaults to 1 1 1.
struct RawOptions {
    std::optional<Vec3i> dims;
    std::optional<ScalarType> type;
    std::optional<Vec3d> spacing;
    bool bigEndian = false;
    std::string series;  // DICOM folders: the SeriesInstanceUID to read; empty for a folder of one series
    bool operator==(const RawOptions&) const = default;
};

// Raw (.raw, .raw.gz), NRRD (.nrrd/.nhdr), MetaImage (.mhd/.mha), NIfTI (.nii/.nii.gz), DICOM series (a folder),
// VTK image data (.vti, legacy .vtk structured points), OpenVDB (.vdb, first float grid, densified over its
// active bounding box), chosen by the (case-insensitive) file name. `raw`'s dims, type, spacing and byte order apply
// to raw files only (given for another format, an InputError naming them), its series to DICOM folders only (a
// series given for a file is an InputError).
// Voxels are x fastest as stored (DICOM rows top first, slices by increasing position along the slice normal);
// spacing comes from the file, and grid.origin is the corner of voxel (0,0,0), half a voxel before the first
// sample's position in the file. Sets sourceType (Float32 for types other than the four, and for rescaled
// NIfTI) and source (= path). Throws InputError naming the file and the problem: unknown format, missing file,
// sizes that do not match, corrupt files, non-finite voxels (with their count and the first one's index).
// The formats but raw are read by volload's modules (format_module.h), loaded on first use: one that cannot be
// loaded is a std::runtime_error naming the path and the module's file.
// Not for concurrent use from several threads (VTK's readers report through process-wide channels).
Volume loadVolume(const std::filesystem::path& path, const RawOptions& raw = {});

// Whether the file name ends as a volume file that loadVolume reads does (any case): .raw, .nii.gz, ...
bool isVolumeFileName(const std::filesystem::path& path);
// Whether loadVolume reads `path` as a headerless raw file (.raw, .raw.gz, in any case): the one the raw options
// describe.
bool isRawFileName(const std::filesystem::path& path);

}  // namespace vr
