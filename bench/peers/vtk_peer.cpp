#include "bench/peers/vtk_peer.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkFloatArray.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
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
// fixed-point mapper, whose nearest sampling truncates the position (voxel v covers [v, v+1) in point units):
// there the points sit on our voxels' corners, so that every voxel covers our cell of it.
vtkSmartPointer<vtkImageData> imageData(const Volume& v, VtkMapper kind) {
    auto image = vtkSmartPointer<vtkImageData>::New();
    const GridGeometry& g = v.grid;
    image->SetDimensions(g.dims.x, g.dims.y, g.dims.z);
    image->SetSpacing(g.spacing.x, g.spacing.y, g.spacing.z);
    const Vec3d first = kind == VtkMapper::FixedPoint ? g.origin : g.origin + g.spacing * 0.5;
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

// Emission-absorption with our TF: nearest sampling, no shading, opacity per our reference step.
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
    p->SetInterpolationTypeToNearest();
    p->ShadeOff();
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

void setCamera(vtkCamera* c, const Camera& cam, const GridGeometry& grid) {
    const double radius = 0.5 * length(grid.extent());
    const Vec3d centre = grid.centre();
    c->ParallelProjectionOn();
    c->SetPosition(cam.eye.x, cam.eye.y, cam.eye.z);
    c->SetFocalPoint(centre.x, centre.y, centre.z);
    c->SetViewUp(cam.up.x, cam.up.y, cam.up.z);
    c->SetParallelScale(cam.halfHeight);  // half the viewport height, as ours
    c->SetClippingRange(0.5 * radius, 3.5 * radius);  // the eye plane is 2 radii from the centre
}

}  // namespace

PeerRun runVtkPeer(const PeerScene& scene, VtkMapper kind, const std::filesystem::path& outDir) {
    if (scene.views.front().projection != Projection::Orthographic)
        throw InputError("vr_peers: only orthographic views are set up for VTK");
    vtkMultiThreader::SetGlobalMaximumNumberOfThreads(scene.options.threads);
    const auto setup = std::chrono::steady_clock::now();
    vtkSmartPointer<vtkImageData> image = imageData(scene.volume, kind);
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
        setCamera(renderer->GetActiveCamera(), scene.views[i], scene.volume.grid);
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
    run.notes = kind == VtkMapper::FixedPoint
                    ? "nearest, ShadeOff, SampleDistance = step x smallest spacing, opacity unit distance = smallest "
                      "spacing; 15-bit fixed-point compositing; points on our voxel corners (its nearest truncates), so the "
                      "last voxel layer on the +x, +y, +z faces is outside its box"
                    : "nearest 3D texture, ShadeOff, no jittering, same sample distance / opacity unit distance; "
                      "8-bit framebuffer; Mesa llvmpipe (LP_NUM_THREADS); its box spans the voxel centres (half a "
                      "voxel inside ours on every face)";
    return run;
}

}  // namespace vr
