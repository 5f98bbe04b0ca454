#include "support/label_maps.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <stdexcept>

#include "preprocess/classify/label_colours.h"

namespace vr::test {

LabelMap thresholdLabels(const Volume& volume, const std::vector<float>& thresholds) {
    LabelMap map;
    map.label.resize(volume.values.size());
    int largest = 0;
    for (std::size_t i = 0; i < volume.values.size(); ++i) {
        int l = 0;
        for (std::size_t t = 0; t < thresholds.size(); ++t)
            if (volume.values[i] >= thresholds[t]) l = int(t) + 1;
        map.label[i] = uint16_t(l);
        largest = std::max(largest, l);
    }
    for (int l = 0; l <= largest; ++l) map.rgba.push_back(defaultLabelColour(l));
    map.source = volume.source + " thresholded";
    return map;
}

void writeNiftiWithVtk(const std::filesystem::path& path, const std::vector<float>& labels, const GridGeometry& grid,
                       ScalarType type) {
    vtkNew<vtkImageData> image;
    image->SetDimensions(grid.dims.x, grid.dims.y, grid.dims.z);
    image->SetSpacing(grid.spacing.x, grid.spacing.y, grid.spacing.z);
    image->AllocateScalars(type == ScalarType::UInt8    ? VTK_UNSIGNED_CHAR
                           : type == ScalarType::Int16  ? VTK_SHORT
                           : type == ScalarType::UInt16 ? VTK_UNSIGNED_SHORT
                                                        : VTK_FLOAT,
                           1);
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    for (std::size_t i = 0; i < labels.size(); ++i) scalars->SetComponent(vtkIdType(i), 0, labels[i]);
    vtkNew<vtkNIFTIImageWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(path.c_str());
    writer->Write();
    if (writer->GetErrorCode() != 0) throw std::runtime_error("vtkNIFTIImageWriter failed on " + path.string());
}

}  // namespace vr::test
