// How a volume, its transfer function and our view are handed to VTK's volume mappers: shared by vr_peers
// (vtk_peer.cpp, every view of an orbit) and vtk_whole_process (one image, the whole process of a VTK user).
#pragma once
#include <vtkSmartPointer.h>

#include "core/volume.h"
#include "preprocess/classify/transfer_function.h"
#include "render/camera.h"
#include "render/image.h"

class vtkCamera;
class vtkFixedPointVolumeRayCastMapper;
class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolumeProperty;

namespace vr {

// The volume as vtkImageData. VTK's points are voxel centres, so the image data starts half a voxel inside our
// grid's corner; `cornerPoints` puts the points on our voxels' corners instead (the fixed-point mapper at nearest,
// whose nearest sampling truncates the position: voxel v covers [v, v+1) in point units).
// vtkImageOf: the scalars copied into the file's own type, so that the mappers tabulate the TF per integer value
// as our classification does.
vtkSmartPointer<vtkImageData> vtkImageOf(const Volume& volume, bool cornerPoints);
// vtkImageViewOf: our float scalars themselves, wrapped without a copy (the volume must outlive the image; VTK
// neither writes nor frees them).
vtkSmartPointer<vtkImageData> vtkImageViewOf(Volume& volume, bool cornerPoints);

// Emission-absorption with our TF (`table`: its samples, piecewise linear between them), opacity per
// `opacityUnitDistance`: nearest sampling and no shading, or with `userSettings` linear interpolation and our Phong
// material (render/span.h ShadingModel), lit by the renderer's headlight (addVtkHeadlight).
vtkSmartPointer<vtkVolumeProperty> vtkVolumePropertyOf(const SampledTransferFunction& table,
                                                       double opacityUnitDistance, bool userSettings);

// vtkFixedPointVolumeRayCastMapper at a fixed sample distance (no automatic adjustment, not locked to the spacing),
// one ray per pixel, `threads` threads.
vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> vtkFixedPointMapperOf(double sampleDistance, int threads);

// Our orthographic camera in VTK's. `distance`: the eye's distance from the centre in multiples of ours (2 radii).
// An orthographic view does not depend on it, but the GPU mapper's headlight does: it shines from the eye's position
// towards each ray's entry point, so far away (kVtkHeadlightDistance) makes it the directional headlight ours is.
constexpr double kVtkHeadlightDistance = 500;  // at 1000 radii within 0.06 degrees of directional
void setVtkCamera(vtkCamera* camera, const Camera& ours, const GridGeometry& grid, double distance = 1);

// One white headlight, as ours, two-sided; its ambient colour white (the fixed-point mapper's ambient term is the
// material's times the light's, black by default; the GPU mapper ignores a headlight's ambient colour).
void addVtkHeadlight(vtkRenderer* renderer);

// An off-screen render window of WIDTH x HEIGHT with the renderer, with alpha planes, no multisampling. VTK's X
// render windows still need an X display (xvfb-run).
vtkSmartPointer<vtkRenderWindow> vtkOffscreenWindow(vtkRenderer* renderer, int width, int height);

// The window's pixels as our image (row 0 = top; VTK's framebuffer holds linear premultiplied RGBA over black).
void readVtkImage(vtkRenderWindow* window, Image& out);

}  // namespace vr
