// NIfTI-1/2 (.nii, .nii.gz) through vtkNIFTIImageReader.
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>

#include "preprocess/load/format_loaders.h"
#include "preprocess/load/header_checks.h"
#include "preprocess/load/vtk/vtk_image_volume.h"
#include "preprocess/load/vtk/vtk_read.h"

namespace vr {

// Voxels come in the file's storage order (x fastest), as the raws converted from the same NIfTI files hold them
// (colin27: equal voxel for voxel). The one change is VTK's own and is kept: for qfac = -1 (a left-handed index
// frame) it reverses the slices, so that the volume does not render mirrored.
Volume loadNifti(const std::filesystem::path& path) {
    checkNiftiHeader(path);
    vtkNew<vtkNIFTIImageReader> reader;
    VtkReadErrors errors;
    reader->SetFileName(path.c_str());
    Volume v = volumeFromVtkImage(errors.read(reader, path, "NIfTI"), path);
    // The reader keeps the stored values; scl_slope/scl_inter calibrate them (colin27 stores NaN: unscaled).
    applyRescale(v, reader->GetRescaleSlope(), reader->GetRescaleIntercept());
    // A series along time (fMRI, perfusion): the reader reads its first volume, as 3D Slicer shows one at first.
    if (const int volumes = reader->GetTimeDimension(); volumes > 1)
        v.notes.push_back("a 4-D NIfTI of " + std::to_string(volumes) + " volumes along time: only the first is read");
    return v;
}

}  // namespace vr
