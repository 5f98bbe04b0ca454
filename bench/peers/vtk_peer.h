// VTK's two volume ray casters on our views: vtkFixedPointVolumeRayCastMapper (CPU) and
// vtkOpenGLGPUVolumeRayCastMapper (OpenGL: Mesa llvmpipe under Xvfb, or a GPU; its notes name the renderer).
// Needs an X display (run under xvfb-run).
#pragma once
#include <filesystem>

#include "bench/peers/peer_run.h"

namespace vr {

enum class VtkMapper { FixedPoint, Gpu };

PeerRun runVtkPeer(const PeerScene& scene, VtkMapper mapper, const std::filesystem::path& outDir);

}  // namespace vr
