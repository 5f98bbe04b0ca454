#include "preprocess/load/format_module.h"

#include <stdexcept>

#include "tools/runtime_module.h"

namespace vr {

Volume loadThroughModule(ModuleFormat format, const std::filesystem::path& path, const RawOptions& options) {
    const bool vdb = format == ModuleFormat::Vdb;
    FormatLoader load = nullptr;
    try {
        load = moduleFunction<decltype(vrFormatLoader)>(
            vdb ? "volload_vdb" : "volload_vtk", "vrFormatLoader",
            vdb ? "reads OpenVDB files" : "reads NRRD, MetaImage, NIfTI, VTK image data and DICOM")(format);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(path.string() + ": " + e.what());
    }
    if (!load) throw std::logic_error("the format module holds no loader of format " + std::to_string(int(format)));
    return load(path, options);
}

}  // namespace vr
