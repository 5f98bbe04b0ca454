// Loading any supported volume file into a vr::Volume (dispatch on the file name / folder).
#pragma once
#include <filesystem>
#include <optional>

#include "core/volume.h"

namespace vr {

// Flags for headerless raw files; dims/type may also be parsed from names like engine_256x256x128_uint8.raw[.gz].
struct RawOptions {
    std::optional<Vec3i> dims;
    std::optional<ScalarType> type;
    std::optional<Vec3d> spacing;
    bool bigEndian = false;
};

// Raw (.raw, .raw.gz), NRRD, MetaImage (.mhd/.mha), NIfTI (.nii/.nii.gz), DICOM series (a folder),
// VTK image data (.vti, legacy .vtk), OpenVDB (.vdb, first float grid, densified).
// Throws InputError naming the file and the problem. Non-finite voxels are rejected (InputError).
Volume loadVolume(const std::filesystem::path& path, const RawOptions& raw = {});

}  // namespace vr
