// volload_vtk.so's one entry (format_module.h).
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/format_module.h"

extern "C" vr::FormatLoader vrFormatLoader(vr::ModuleFormat format) {
    using namespace vr;
    switch (format) {
        case ModuleFormat::Nrrd: return ignoringRawOptions<loadNrrd>;
        case ModuleFormat::MetaImage: return ignoringRawOptions<loadMetaImage>;
        case ModuleFormat::Nifti: return ignoringRawOptions<loadNifti>;
        case ModuleFormat::VtkXmlImage: return ignoringRawOptions<loadVtkXmlImage>;
        case ModuleFormat::VtkLegacy: return ignoringRawOptions<loadVtkLegacy>;
        case ModuleFormat::DicomSeries:
            return [](const std::filesystem::path& folder, const RawOptions& raw) {
                return loadDicomSeries(folder, raw.series);
            };
        case ModuleFormat::Vdb: break;
    }
    return nullptr;
}
