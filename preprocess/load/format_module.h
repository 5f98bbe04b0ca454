// What volload shares with its format modules (tools/runtime_module.h): volload_vtk.so holds the loaders of the
// formats VTK reads (preprocess/load/vtk/), volload_vdb.so OpenVDB's (preprocess/load/vdb/). A module is loaded
// when a file of its formats is: VTK's readers and OpenVDB (with Blosc, Boost and log4cplus) would otherwise be
// loaded and relocated at every start of every tool (OpenVDB alone: tens of thousands of symbol bindings).
#pragma once
#include <filesystem>

#include "core/volume.h"
#include "preprocess/load/load_volume.h"

namespace vr {

enum class ModuleFormat { Nrrd, MetaImage, Nifti, VtkXmlImage, VtkLegacy, DicomSeries, Vdb };

// A format's loader (format_loaders.h): the raw options give a DICOM folder its series; the other formats ignore
// them.
using FormatLoader = Volume (*)(const std::filesystem::path& path, const RawOptions& options);

template <Volume (*load)(const std::filesystem::path&)>
Volume ignoringRawOptions(const std::filesystem::path& path, const RawOptions&) {
    return load(path);
}

// Loads `path` with the loader of `format` from its module, loading the module the first time. Throws what the
// loader throws, and std::runtime_error naming `path`, the module's file and why it cannot be loaded.
Volume loadThroughModule(ModuleFormat format, const std::filesystem::path& path, const RawOptions& options);

}  // namespace vr

// Each format module's entry: its loader of `format`, nullptr for a format it does not hold.
extern "C" vr::FormatLoader vrFormatLoader(vr::ModuleFormat format);
