#include "bench/peers/vtk_peer.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkMultiThreader.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <chrono>

#include "bench/peers/vtk_setup.h"
#include "core/errors.h"

namespace vr {
namespace {

vtkSmartPointer<vtkVolumeMapper> makeMapper(const PeerScene& scene, VtkMapper kind) {
    const double dt = scene.sampleDistance();
    if (kind == VtkMapper::FixedPoint) return vtkFixedPointMapperOf(dt, scene.options.threads);
    auto m = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
    m->AutoAdjustSampleDistancesOff();
    m->LockSampleDistanceToInputSpacingOff();
    m->SetSampleDistance(float(dt));
    m->SetImageSampleDistance(1.0f);
    m->SetUseJittering(0);
    return m;
}

// What differs from our renderer, per mapper and settings.
const char* notes(VtkMapper kind, bool userSettings) {
    if (userSettings)
        return kind == VtkMapper::FixedPoint
                   ? "linear (scalars interpolated, then classified), ShadeOn with our material and a white headlight, "
                     "two-sided; shaded per voxel from quantised gradient directions (vtkEncodedGradientShader: "
                     "Blinn-Phong, (N.H)^24), the 8 voxels' shaded colours interpolated, flat voxels ambient only; "
                     "same sample distance / opacity unit distance; 15-bit fixed-point compositing; points on our "
                     "voxel centres (half a voxel inside ours on every face); the gradients are computed in the "
                     "warm-up render (in neither setup nor the views)"
                   : "linear 3D texture, ShadeOn with our material and a white headlight, two-sided; gradient per "
                     "sample (central differences on the texture), Blinn-Phong (N.H)^24 (with a headlight a wider "
                     "highlight than our (R.V)^24), flat samples ambient only; no jittering, same sample distance / "
                     "opacity unit distance; 8-bit framebuffer; its box spans the "
                     "voxel centres (half a voxel inside ours on every face)";
    return kind == VtkMapper::FixedPoint
               ? "nearest, ShadeOff, SampleDistance = step x smallest spacing, opacity unit distance = smallest "
                 "spacing; 15-bit fixed-point compositing; points on our voxel corners (its nearest truncates), so the "
                 "last voxel layer on the +x, +y, +z faces is outside its box"
               : "nearest 3D texture, ShadeOff, no jittering, same sample distance / opacity unit distance; "
                 "8-bit framebuffer; its box spans the voxel centres (half a voxel inside ours on every face)";
}

// The OpenGL renderer of the window's context, once it has rendered: Mesa llvmpipe under Xvfb (LP_NUM_THREADS
// threads), or the GPU whose driver serves the display.
std::string openGlRenderer(vtkRenderWindow* window) {
    const std::string capabilities = window->ReportCapabilities();
    const std::string key = "OpenGL renderer string:";
    const std::size_t at = capabilities.find(key);
    if (at == std::string::npos) return "not reported";
    const std::size_t from = capabilities.find_first_not_of(' ', at + key.size());
    return capabilities.substr(from, capabilities.find('\n', from) - from);
}

}  // namespace

PeerRun runVtkPeer(const PeerScene& scene, VtkMapper kind, const std::filesystem::path& outDir) {
    if (scene.views.front().projection != Projection::Orthographic)
        throw InputError("vr_peers: only orthographic views are set up for VTK");
    vtkMultiThreader::SetGlobalMaximumNumberOfThreads(scene.options.threads);
    const auto setup = std::chrono::steady_clock::now();
    const bool user = scene.options.userSettings;
    // The scalars in the source type (a copy): the mappers tabulate the TF per integer value, as our classification
    // does. The fixed-point mapper at nearest gets its points on our voxels' corners (its nearest truncates); its
    // linear interpolation blends the points around the sample, as ours blends the voxel centres: centres there.
    vtkSmartPointer<vtkImageData> image = vtkImageOf(scene.volume, kind == VtkMapper::FixedPoint && !user);
    vtkSmartPointer<vtkVolumeMapper> mapper = makeMapper(scene, kind);
    mapper->SetInputData(image);
    if (scene.options.blend == Blend::MIP)
        mapper->SetBlendModeToMaximumIntensity();
    else
        mapper->SetBlendModeToComposite();
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    volume->SetProperty(vtkVolumePropertyOf(scene.table, scene.referenceStep(), user));

    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0, 0, 0);
    renderer->SetBackgroundAlpha(0);
    renderer->AddVolume(volume);
    if (user) addVtkHeadlight(renderer);
    vtkSmartPointer<vtkRenderWindow> window =
        vtkOffscreenWindow(renderer, scene.options.width, scene.options.height);
    const double setupMs = millisecondsSince(setup);

    const char* name = kind == VtkMapper::FixedPoint ? "vtk-fixed-point" : "vtk-gpu";
    PeerRun run = runViews(name, scene, outDir, [&](std::size_t i, Image& out) {
        setVtkCamera(renderer->GetActiveCamera(), scene.views[i], scene.volume.grid,
                     user ? kVtkHeadlightDistance : 1);
        const auto start = std::chrono::steady_clock::now();
        window->Render();
        window->WaitForCompletion();
        const double ms = millisecondsSince(start);
        readVtkImage(window, out);
        return ms;
    });
    run.setupMs = setupMs;
    run.notes = scene.options.blend == Blend::MIP
                    ? std::string("SetBlendModeToMaximumIntensity (shading unused); ") + notes(kind, user)
                    : std::string(notes(kind, user));
    if (kind == VtkMapper::Gpu) run.notes += "; OpenGL renderer: " + openGlRenderer(window);
    return run;
}

}  // namespace vr
