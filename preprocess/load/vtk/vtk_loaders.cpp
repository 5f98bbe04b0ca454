// Formats VTK reads as they are: NRRD, MetaImage, VTK XML image data and legacy structured points.
#include <vtkImageData.h>
#include <vtkMetaImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkStructuredPointsReader.h>
#include <vtkXMLImageDataReader.h>

#include "core/errors.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/vtk/vtk_image_volume.h"
#include "preprocess/load/vtk/vtk_read.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

template <typename Reader>
Volume readWith(const fs::path& path, const std::string& format) {
    vtkNew<Reader> reader;
    VtkReadErrors errors;
    if constexpr (std::is_base_of_v<vtkXMLReader, Reader>) reader->SetParserErrorObserver(errors.observer());
    reader->SetFileName(path.c_str());
    return volumeFromVtkImage(errors.read(reader, path, format), path);
}

}  // namespace

Volume loadMetaImage(const fs::path& path) {
    checkMetaImageHeader(path);
    return readWith<vtkMetaImageReader>(path, "MetaImage");
}
Volume loadVtkXmlImage(const fs::path& path) {
    checkVtkXmlImageFile(path);
    return readWith<vtkXMLImageDataReader>(path, "VTK XML image data");
}
Volume loadVtkLegacy(const fs::path& path) {
    checkVtkLegacyFile(path);
    return readWith<vtkStructuredPointsReader>(path, "VTK structured points");
}

Volume loadNrrd(const fs::path& path) {
    checkNrrdFile(path);
    vtkNew<vtkNrrdReader> reader;
    VtkReadErrors errors;
    reader->SetFileName(path.c_str());
    vtkImageData* image = errors.read(reader, path, "NRRD");
    // NRRD does not tell vector axes from domain axes; VTK guesses that a first axis of 9 samples or fewer holds
    // components, so a scalar volume that narrow reads as vectors.
    if (const int n = image->GetNumberOfScalarComponents(); n > 1)
        throw fileError(path.string(), "VTK's NRRD reader reads its first axis as " + std::to_string(n) +
                                           " components per voxel (it does so for axes of 9 samples or fewer); "
                                           "only scalar volumes are supported");
    return volumeFromVtkImage(image, path);
}

}  // namespace vr
