#include "bench/peers/vtk_peer.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkFloatArray.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkMultiThreader.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkShortArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <chrono>

#include "core/errors.h"

namespace vr {
namespace {

template <class ArrayT>
vtkSmartPointer<vtkDataArray> scalarArray(const Volume& v) {
    auto a = vtkSmartPointer<ArrayT>::New();
    a->SetNumberOfTuples(vtkIdType(v.values.size()));
    for (std::size_t i = 0; i < v.values.size(); ++i) a->SetValue(vtkIdType(i), typename ArrayT::ValueType(v.values[i]));
    return a;
}

// The source type, so that the mappers tabulate the TF per integer value as our classification does.
// VTK's points are voxel centres, so the image data starts half a voxel inside our grid's corner; except for the
// fixed-point mapper at nearest, whose nearest sampling truncates the position (voxel v covers [v, v+1) in point
// units): there the points sit on our voxels' corners, so that every voxel covers our cell of it. Its linear
// interpolation blends the points around the sample, as ours blends the voxel centres: centres there.
vtkSmartPointer<vtkImageData> imageData(const Volume& v, bool cornerPoints) {
    auto image = vtkSmartPointer<vtkImageData>::New();
    const GridGeometry& g = v.grid;
    image->SetDimensions(g.dims.x, g.dims.y, g.dims.z);
    image->SetSpacing(g.spacing.x, g.spacing.y, g.spacing.z);
    const Vec3d first = cornerPoints ? g.origin : g.origin + g.spacing * 0.5;
    image->SetOrigin(first.x, first.y, first.z);
    vtkSmartPointer<vtkDataArray> scalars;
    switch (v.sourceType) {
        case ScalarType::UInt8: scalars = scalarArray<vtkUnsignedCharArray>(v); break;
        case ScalarType::Int16: scalars = scalarArray<vtkShortArray>(v); break;
        case ScalarType::UInt16: scalars = scalarArray<vtkUnsignedShortArray>(v); break;
        case ScalarType::Float32: scalars = scalarArray<vtkFloatArray>(v); break;
    }
    image->GetPointData()->SetScalars(scalars);
    return image;
}

// Emission-absorption with our TF, opacity per our reference step: nearest sampling and no shading, or at the user
// settings linear interpolation and our Phong material (render/span.h ShadingModel), lit by the renderer's headlight.
vtkSmartPointer<vtkVolumeProperty> volumeProperty(const PeerScene& scene) {
    const SampledTransferFunction& t = scene.table;
    const int n = int(t.opacity.size());
    const double hi = t.lo + t.step * (n - 1);
    std::vector<double> opacity(t.opacity), rgb;
    for (const auto& c : t.colour) rgb.insert(rgb.end(), {c[0], c[1], c[2]});
    vtkNew<vtkPiecewiseFunction> opacityFn;
    opacityFn->BuildFunctionFromTable(t.lo, hi, n, opacity.data());
    vtkNew<vtkColorTransferFunction> colourFn;
    colourFn->BuildFunctionFromTable(t.lo, hi, n, rgb.data());

    auto p = vtkSmartPointer<vtkVolumeProperty>::New();
    p->SetColor(colourFn);
    p->SetScalarOpacity(opacityFn);
    p->SetScalarOpacityUnitDistance(scene.referenceStep());
    if (scene.options.userSettings) {
        const ShadingModel m;
        p->SetInterpolationTypeToLinear();
        p->ShadeOn();
        p->SetAmbient(m.ambient);
        p->SetDiffuse(m.diffuse);
        p->SetSpecular(m.specular);
        p->SetSpecularPower(m.shininess);
    } else {
        p->SetInterpolationTypeToNearest();
        p->ShadeOff();
    }
    p->IndependentComponentsOn();
    return p;
}

vtkSmartPointer<vtkVolumeMapper> makeMapper(const PeerScene& scene, VtkMapper kind) {
    const double dt = scene.sampleDistance();
    if (kind == VtkMapper::FixedPoint) {
        auto m = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
        m->AutoAdjustSampleDistancesOff();
        m->LockSampleDistanceToInputSpacingOff();
        m->SetSampleDistance(dt);
        m->SetInteractiveSampleDistance(dt);
        m->SetImageSampleDistance(1.0);
        m->SetNumberOfThreads(scene.options.threads);
        m->IntermixIntersectingGeometryOff();
        return m;
    }
    auto m = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
    m->AutoAdjustSampleDistancesOff();
    m->LockSampleDistanceToInputSpacingOff();
    m->SetSampleDistance(float(dt));
    m->SetImageSampleDistance(1.0f);
    m->SetUseJittering(0);
    return m;
}

// `distance`: the eye's distance from the centre in multiples of ours (2 radii). An orthographic view does not
// depend on it, but the GPU mapper's headlight does: it shines from the eye's position towards each ray's entry
// point, so far away makes it the directional headlight ours is (at 1000 radii within 0.06 degrees).
void setCamera(vtkCamera* c, const Camera& cam, const GridGeometry& grid, double distance = 1) {
    const double radius = 0.5 * length(grid.extent());
    const Vec3d centre = grid.centre();
    const Vec3d eye = centre + (cam.eye - centre) * distance;
    c->ParallelProjectionOn();
    c->SetPosition(eye.x, eye.y, eye.z);
    c->SetFocalPoint(centre.x, centre.y, centre.z);
    c->SetViewUp(cam.up.x, cam.up.y, cam.up.z);
    c->SetParallelScale(cam.halfHeight);  // half the viewport height, as ours
    const double d = 2 * radius * distance;  // ours: the eye plane is 2 radii from the centre
    c->SetClippingRange(d - 1.5 * radius, d + 1.5 * radius);
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
                     "opacity unit distance; 8-bit framebuffer; Mesa llvmpipe (LP_NUM_THREADS); its box spans the "
                     "voxel centres (half a voxel inside ours on every face)";
    return kind == VtkMapper::FixedPoint
               ? "nearest, ShadeOff, SampleDistance = step x smallest spacing, opacity unit distance = smallest "
                 "spacing; 15-bit fixed-point compositing; points on our voxel corners (its nearest truncates), so the "
                 "last voxel layer on the +x, +y, +z faces is outside its box"
               : "nearest 3D texture, ShadeOff, no jittering, same sample distance / opacity unit distance; "
                 "8-bit framebuffer; Mesa llvmpipe (LP_NUM_THREADS); its box spans the voxel centres (half a "
                 "voxel inside ours on every face)";
}

}  // namespace

PeerRun runVtkPeer(const PeerScene& scene, VtkMapper kind, const std::filesystem::path& outDir) {
    if (scene.views.front().projection != Projection::Orthographic)
        throw InputError("vr_peers: only orthographic views are set up for VTK");
    vtkMultiThreader::SetGlobalMaximumNumberOfThreads(scene.options.threads);
    const auto setup = std::chrono::steady_clock::now();
    const bool user = scene.options.userSettings;
    vtkSmartPointer<vtkImageData> image = imageData(scene.volume, kind == VtkMapper::FixedPoint && !user);
    vtkSmartPointer<vtkVolumeMapper> mapper = makeMapper(scene, kind);
    mapper->SetInputData(image);
    mapper->SetBlendModeToComposite();
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    volume->SetProperty(volumeProperty(scene));

    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(0, 0, 0);
    renderer->SetBackgroundAlpha(0);
    renderer->AddVolume(volume);
    if (user) {
        // One white headlight, as ours (VTK would make one by itself when there is none: here it is explicit). Its
        // ambient colour is white: the fixed-point mapper's ambient term is the material's times the light's (black
        // by default); the GPU mapper ignores a headlight's ambient colour.
        vtkNew<vtkLight> light;
        light->SetLightTypeToHeadlight();
        light->SetColor(1, 1, 1);
        light->SetAmbientColor(1, 1, 1);
        light->SetIntensity(1);
        renderer->AutomaticLightCreationOff();
        renderer->LightFollowCameraOn();
        renderer->TwoSidedLightingOn();  // ours is two-sided: the normal is turned to face the viewer
        renderer->AddLight(light);
    }
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->SetAlphaBitPlanes(1);
    window->SetMultiSamples(0);
    window->SetSize(scene.options.width, scene.options.height);
    window->AddRenderer(renderer);
    const double setupMs = millisecondsSince(setup);

    const int w = scene.options.width, h = scene.options.height;
    vtkNew<vtkFloatArray> pixels;
    const char* name = kind == VtkMapper::FixedPoint ? "vtk-fixed-point" : "vtk-gpu-llvmpipe";
    PeerRun run = runViews(name, scene, outDir, [&](std::size_t i, Image& out) {
        setCamera(renderer->GetActiveCamera(), scene.views[i], scene.volume.grid, user ? 500 : 1);
        const auto start = std::chrono::steady_clock::now();
        window->Render();
        window->WaitForCompletion();
        const double ms = millisecondsSince(start);
        window->GetRGBAPixelData(0, 0, w - 1, h - 1, 1, pixels, 0);
        for (int y = 0; y < h; ++y)  // OpenGL's row 0 is the bottom
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c)
                    out.pixel(x, y)[c] = pixels->GetValue((vtkIdType(h - 1 - y) * w + x) * 4 + c);
        return ms;
    });
    run.setupMs = setupMs;
    run.notes = notes(kind, user);
    return run;
}

}  // namespace vr
