// vtk_whole_process: in one process, what a VTK user's script does from the source volume file to the first image
// with VTK's fixed-point CPU ray caster, at the settings our one command (`volrender VOLUME --tf TF.json`) renders
// with: read the volume, build the transfer function, set up vtkFixedPointVolumeRayCastMapper (linear
// interpolation, ShadeOn with our Phong material and one white headlight, as `vr_peers --user-settings`), render
// one image off screen from our orthographic camera and write it as PNG. scripts/whole_process.sh times it (wall
// seconds and peak resident memory) beside volrender (docs/BENCH.md "What users feel").
//
// The volume is read by our loader (vr::loadVolume: every format volrender reads, and the NAME_XxYxZ_TYPE.raw.gz
// naming of the shared datasets, which no VTK reader reads: vtkImageReader2 reads raw files but not gzip ones) and
// handed to VTK without a copy: the float scalars our loader holds, wrapped in a vtkFloatArray. VTK reads .vti,
// legacy .vtk (our loader uses those very readers), .mhd/.mha, .nii and DICOM folders natively; a user reading an
// integer file so holds the file's type (1-2 bytes per voxel) where this process holds float (4).
// The TF is the peers' table (bench/peers/peer_scene.h: our TF at every integer value), opacity per the smallest
// spacing, sample distance STEP x the smallest spacing (STEP 0.5 as ours). Needs an X display (xvfb-run), as every
// VTK render window on Linux does, even off screen.
#include <tbb/global_control.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkMultiThreader.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkVersion.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/peers/peer_scene.h"
#include "bench/peers/vtk_setup.h"
#include "core/errors.h"
#include "preprocess/classify/transfer_choice.h"

namespace {

double secondsSince(std::chrono::steady_clock::time_point& start) {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - start).count();
    start = now;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"VTK's fixed-point CPU ray caster from the source volume file to one PNG, in one process, at the "
                 "settings volrender renders with (trilinear, shaded, orthographic, 512x512); see docs/BENCH.md"};
    std::string volumePath, tfPath, size = "512x512", out;
    std::vector<double> spacing;
    double azimuth = 0, elevation = 0, step = 0.5;
    int threads = 2;
    app.add_option("volume", volumePath, "volume file (any format volrender reads, e.g. NAME_XxYxZ_TYPE.raw.gz)")
        ->required();
    app.add_option("--tf", tfPath, "a built-in preset's name or a ParaView transfer function preset (JSON)")
        ->required();
    app.add_option("--spacing", spacing, "voxel size x,y,z for raw volumes")->delimiter(',')->expected(3);
    app.add_option("--size", size, "image size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--azimuth", azimuth, "camera turn about the up axis, degrees")->capture_default_str();
    app.add_option("--elevation", elevation, "camera turn about the right axis, degrees")->capture_default_str();
    app.add_option("--step", step, "sample distance in voxels of the smallest spacing")->capture_default_str();
    app.add_option("--threads", threads, "VTK's threads (the mapper's and vtkMultiThreader's global maximum)")
        ->capture_default_str();
    app.add_option("-o,--output", out, "PNG to write (8-bit sRGB-encoded, as volrender's)")->required();
    CLI11_PARSE(app, argc, argv);

    try {
        vr::ViewParams view;
        char extra = 0;
        if (std::sscanf(size.c_str(), "%dx%d%c", &view.width, &view.height, &extra) != 2 || view.width < 1 ||
            view.height < 1)
            throw vr::InputError("--size " + size + ": expected WIDTHxHEIGHT");
        if (threads < 1) throw vr::InputError("--threads must be at least 1");
        if (!(step > 0) || !std::isfinite(step)) throw vr::InputError("--step must be a positive number");
        view.azimuthDeg = azimuth;
        view.elevationDeg = elevation;
        // llvmpipe (which only draws the mapper's finished image) reads its thread count when the first OpenGL
        // context is made; TBB serves our loader.
        setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
        tbb::global_control tbbThreads(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        vtkMultiThreader::SetGlobalMaximumNumberOfThreads(threads);

        auto clock = std::chrono::steady_clock::now();
        vr::RawOptions raw;
        if (!spacing.empty()) raw.spacing = vr::Vec3d{spacing[0], spacing[1], spacing[2]};
        vr::Volume volume = vr::loadVolume(volumePath, raw);
        vtkSmartPointer<vtkImageData> image = vr::vtkImageViewOf(volume, /*cornerPoints*/ false);
        const double loadS = secondsSince(clock);

        const vr::SampledTransferFunction table = vr::peerTable(volume, vr::namedTransferFunction(tfPath));
        const double unit = volume.grid.smallestSpacing();  // our TF's opacity is per this length
        vtkSmartPointer<vtkVolumeProperty> property = vr::vtkVolumePropertyOf(table, unit, /*userSettings*/ true);
        const double tfS = secondsSince(clock);

        vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> mapper = vr::vtkFixedPointMapperOf(step * unit, threads);
        mapper->SetInputData(image);
        mapper->SetBlendModeToComposite();
        vtkNew<vtkVolume> actor;
        actor->SetMapper(mapper);
        actor->SetProperty(property);
        vtkNew<vtkRenderer> renderer;
        renderer->SetBackground(0, 0, 0);
        renderer->SetBackgroundAlpha(0);
        renderer->AddVolume(actor);
        vr::addVtkHeadlight(renderer);
        vr::setVtkCamera(renderer->GetActiveCamera(), vr::Camera::fit(volume.grid, view), volume.grid,
                         vr::kVtkHeadlightDistance);
        vtkSmartPointer<vtkRenderWindow> window = vr::vtkOffscreenWindow(renderer, view.width, view.height);
        const double setupS = secondsSince(clock);

        window->Render();  // the first render: the gradients for shading, the tables, then the rays
        window->WaitForCompletion();
        const double renderS = secondsSince(clock);

        vr::Image picture(view.width, view.height);
        vr::readVtkImage(window, picture);
        vr::writeImage(out, picture);
        const double writeS = secondsSince(clock);

        std::printf("vtk_whole_process (VTK %s, vtkFixedPointVolumeRayCastMapper, %d thread(s)): %dx%d, "
                    "%dx%dx%d voxels, %s scalars wrapped as float without a copy\n",
                    vtkVersion::GetVTKVersion(), threads, view.width, view.height, volume.grid.dims.x,
                    volume.grid.dims.y, volume.grid.dims.z, std::string(vr::scalarTypeName(volume.sourceType)).c_str());
        std::printf("seconds: load %.3f, transfer function %.3f, set-up %.3f, render %.3f, read back and write "
                    "%.3f; wrote %s\n",
                    loadS, tfS, setupS, renderS, writeS, out.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vtk_whole_process: %s\n", e.what());
        return 1;
    }
    return 0;
}
