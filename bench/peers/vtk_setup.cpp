#include "bench/peers/vtk_setup.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkShortArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>
#include <vtkVolumeProperty.h>

#include <vector>

#include "render/span.h"

namespace vr {
namespace {

template <class ArrayT>
vtkSmartPointer<vtkDataArray> scalarArray(const Volume& v) {
    auto a = vtkSmartPointer<ArrayT>::New();
    a->SetNumberOfTuples(vtkIdType(v.values.size()));
    for (std::size_t i = 0; i < v.values.size(); ++i)
        a->SetValue(vtkIdType(i), typename ArrayT::ValueType(v.values[i]));
    return a;
}

vtkSmartPointer<vtkImageData> imageGeometry(const GridGeometry& g, bool cornerPoints) {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(g.dims.x, g.dims.y, g.dims.z);
    image->SetSpacing(g.spacing.x, g.spacing.y, g.spacing.z);
    const Vec3d first = cornerPoints ? g.origin : g.origin + g.spacing * 0.5;
    image->SetOrigin(first.x, first.y, first.z);
    return image;
}

}  // namespace

vtkSmartPointer<vtkImageData> vtkImageOf(const Volume& v, bool cornerPoints) {
    vtkSmartPointer<vtkImageData> image = imageGeometry(v.grid, cornerPoints);
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

vtkSmartPointer<vtkImageData> vtkImageViewOf(Volume& v, bool cornerPoints) {
    vtkSmartPointer<vtkImageData> image = imageGeometry(v.grid, cornerPoints);
    vtkNew<vtkFloatArray> scalars;
    scalars->SetArray(v.values.data(), vtkIdType(v.values.size()), /*save: VTK does not free it*/ 1);
    image->GetPointData()->SetScalars(scalars);
    return image;
}

vtkSmartPointer<vtkVolumeProperty> vtkVolumePropertyOf(const SampledTransferFunction& t, double opacityUnitDistance,
                                                       bool userSettings) {
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
    p->SetScalarOpacityUnitDistance(opacityUnitDistance);
    if (userSettings) {
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

vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> vtkFixedPointMapperOf(double dt, int threads) {
    auto m = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
    m->AutoAdjustSampleDistancesOff();
    m->LockSampleDistanceToInputSpacingOff();
    m->SetSampleDistance(dt);
    m->SetInteractiveSampleDistance(dt);
    m->SetImageSampleDistance(1.0);
    m->SetNumberOfThreads(threads);
    m->IntermixIntersectingGeometryOff();
    return m;
}

void setVtkCamera(vtkCamera* c, const Camera& cam, const GridGeometry& grid, double distance) {
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

void addVtkHeadlight(vtkRenderer* renderer) {
    // VTK would make one by itself when there is none: here it is explicit.
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

vtkSmartPointer<vtkRenderWindow> vtkOffscreenWindow(vtkRenderer* renderer, int width, int height) {
    auto window = vtkSmartPointer<vtkRenderWindow>::New();
    window->SetOffScreenRendering(1);
    window->SetAlphaBitPlanes(1);
    window->SetMultiSamples(0);
    window->SetSize(width, height);
    window->AddRenderer(renderer);
    return window;
}

void readVtkImage(vtkRenderWindow* window, Image& out) {
    const int w = out.width, h = out.height;
    vtkNew<vtkFloatArray> pixels;
    window->GetRGBAPixelData(0, 0, w - 1, h - 1, 1, pixels, 0);
    for (int y = 0; y < h; ++y)  // OpenGL's row 0 is the bottom
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) out.pixel(x, y)[c] = pixels->GetValue((vtkIdType(h - 1 - y) * w + x) * 4 + c);
}

}  // namespace vr
