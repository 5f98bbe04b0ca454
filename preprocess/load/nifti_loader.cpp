// NIfTI-1/2 (.nii, .nii.gz) through vtkNIFTIImageReader.
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>

#include "preprocess/load/format_loaders.h"
#include "preprocess/load/vtk_image_volume.h"
#include "preprocess/load/vtk_read.h"

namespace vr {

// Voxels come in the file's storage order (x fastest), which is what the converted raws of the same data hold
// (colin27: equal voxel for voxel). VTK would reverse the slices only for qfac = -1, as NIfTI's left-handed
// index frame demands of a right-handed VTK image; the file's index order is kept as VTK gives it.
Volume loadNifti(const std::filesystem::path& path) {
    vtkNew<vtkNIFTIImageReader> reader;
    VtkReadErrors errors;
    reader->SetFileName(path.c_str());
    Volume v = volumeFromVtkImage(errors.read(reader, path, "NIfTI"), path);
    // The reader keeps the stored values; scl_slope/scl_inter calibrate them (colin27 stores NaN: unscaled).
    applyRescale(v, reader->GetRescaleSlope(), reader->GetRescaleIntercept());
    return v;
}

}  // namespace vr
