// Shared by the CPU and Vulkan stiff / extreme-case tests: synthetic prepared volumes built straight from
// per-voxel opacity and colour, exact cameras (rays through chosen grid points), and the checks every caster
// must pass whichever renderer runs it. The cases themselves live in render_cases.cpp so that the CPU reference
// and the Vulkan casters face exactly the same inputs.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "core/prepared_volume.h"
#include "render/camera.h"
#include "render/render_result.h"
#include "support/views.h"

namespace vr::test {

using RenderFn = std::function<RenderResult(const PreparedVolume&, const Camera&, const RenderSettings&)>;

// The CPU reference renderer (renderCpu) as a RenderFn.
extern const RenderFn kCpuReference;

inline constexpr Caster kCasters[] = {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD, Caster::Hier};

struct VoxelClass {
    double alpha;  // opacity per reference step
    Vec3d colour;
};

// A prepared volume from a per-voxel class (opacity and colour): each distinct class an entry of the transfer
// table, each voxel's scalar (uint16) its entry. Regions for nearest sampling at thresholds 0 (normals unused),
// with PC, ACD and EACD. Throws std::invalid_argument for more than 65536 classes.
PreparedVolume syntheticPrepared(const GridGeometry& grid, double referenceStep,
                                 const std::function<VoxelClass(const Vec3i&)>& voxel);

// syntheticPrepared written as a prepared file into a fresh scratch folder `name` (test::scratchDir): the input the
// command-line tests give the tools.
std::filesystem::path writtenSynthetic(const std::string& name, const GridGeometry& grid, double referenceStep,
                                       const std::function<VoxelClass(const Vec3i&)>& voxel);

// How many inputs (renders) a case family tried, for the report.
struct CaseCount {
    int renders = 0;
    int rays = 0;  // rays cast, per caster
    int hits = 0;  // of them, rays that sampled the volume (compared samples where casters are compared)
};

// Prints what a case family tried, and fails the test where it rendered nothing, cast no ray or no ray sampled the
// volume: a family that tried nothing has checked nothing.
void report(const char* family, const CaseCount& n);

// Every case family runs on one renderer; this bounds what it is asked where it cannot do it all (llvmpipe).
struct CaseOptions {
    // Most lattice samples asked of primitive and PC where they step one sample per fetch (llvmpipe ends a shader
    // after 65535 loop iterations in all, about 3,000 fetches: the renderer then reports an error).
    int64_t maxSteppedSamples = INT64_MAX;
    // Positions and the lattice in float (the Vulkan casters, docs/ALGORITHMS.md section 8): at a step far below
    // float's resolution of t, the lattice of dt rounded to float may count one sample fewer or more, and a leap
    // ends up to 2^-18 T / dt samples before its box's faces (its slack).
    bool floatLattice = false;
};

// A render of the Vulkan casters against the CPU reference's of the same inputs. The device's float positions
// (docs/ALGORITHMS.md section 8) now and then put a sample that lies within float's position error (about 1e-5
// voxels) of a voxel face in the neighbouring voxel: that pixel differs by the sample's share (up to 0.018 on the
// shared volumes), on at most 0.5 % of the pixels. The mean difference stays below 1e-4 and the mean iterations
// within 1 %.
void expectNearCpuReference(const RenderResult& device, const RenderResult& cpu);

CaseCount spanOpacityGrid(const RenderFn& render, const CaseOptions& options);
CaseCount thinSlabsAgainstTheLatticeSum(const RenderFn& render, const CaseOptions& options);
CaseCount hugeRegionAgainstTheClosedForm(const RenderFn& render, const CaseOptions& options);
CaseCount earlyTerminationHitExactly(const RenderFn& render);
CaseCount extremeGeometry(const RenderFn& render);
CaseCount transparentOpaqueAndCappedRegions(const RenderFn& render);
CaseCount iterationCapIsAnError(const RenderFn& render);

}  // namespace vr::test
