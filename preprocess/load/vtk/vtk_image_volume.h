// Copying a vtkImageData read from a file into a Volume.
#pragma once
#include <filesystem>

#include "core/volume.h"

class vtkImageData;

namespace vr {

// One-component scalars only. unsigned char/short/unsigned short/float keep their ScalarType; any other VTK type
// (int, double, ...) is converted to float and recorded as Float32. Rows stay as VTK holds them (x fastest).
// VTK's origin is the position of the first sample (a voxel centre); Volume::grid.origin is the corner of voxel
// (0,0,0), half a voxel before it. A direction matrix (VTK 9 images may carry one) is not applied: the volume
// stays axis-aligned. Throws InputError naming `path` for images that cannot be a Volume.
Volume volumeFromVtkImage(vtkImageData* image, const std::filesystem::path& path);

// Calibrates stored values as value * slope + intercept (NIfTI scl_slope/scl_inter, DICOM rescale). A slope of 0
// or NaN means "unscaled" by NIfTI's rule, as does the identity; a calibrated volume is recorded as Float32.
void applyRescale(Volume& volume, double slope, double intercept);

// Reverses the order of the voxels along `axis` (0 = x, 1 = y, 2 = z), keeping the grid geometry.
void flipAxis(Volume& volume, int axis);

}  // namespace vr
