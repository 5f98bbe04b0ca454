// One loader per file format; loadVolume() picks one by the file name. Each throws InputError naming the file.
// They fill grid, sourceType and values; loadVolume() adds the checks every format shares. The raw loader is
// volload's; the others are its modules' (format_module.h): VTK's formats in volload_vtk (preprocess/load/vtk/),
// OpenVDB in volload_vdb (preprocess/load/vdb/).
#pragma once
#include <filesystem>

#include "core/volume.h"
#include "preprocess/load/load_volume.h"

namespace vr {

Volume loadRaw(const std::filesystem::path& path, const RawOptions& options);  // .raw, .raw.gz
Volume loadNrrd(const std::filesystem::path& path);                            // .nrrd, .nhdr
Volume loadMetaImage(const std::filesystem::path& path);                       // .mhd, .mha
Volume loadNifti(const std::filesystem::path& path);                           // .nii, .nii.gz
// A folder of slices: its one series, or the series `seriesUid` names (SeriesInstanceUID), which a folder holding
// several needs; InputError listing the series otherwise.
Volume loadDicomSeries(const std::filesystem::path& folder, const std::string& seriesUid);
Volume loadVtkXmlImage(const std::filesystem::path& path);                     // .vti
Volume loadVtkLegacy(const std::filesystem::path& path);                       // .vtk (structured points)
Volume loadVdb(const std::filesystem::path& path);                             // .vdb

}  // namespace vr
