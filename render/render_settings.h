// What a render is asked to do: caster, view, step, shading. Shared by the CPU reference and Vulkan.
#pragma once
#include <optional>
#include <string_view>
#include <vector>

#include "core/vec3.h"

namespace vr {

// Blocks leaps by the per-block scalar extrema (render/block_extrema.h): the leap of the blends other than composite,
// whose results follow the scalar, not the classification the regions of PC, ACD and EACD are made of. Hier leaps
// by the hierarchical EACD, an EACD over blocks of voxels (core/distance_fields.h BlockEACD).
enum class Caster { Primitive, PC, ACD, EACD, Blocks, Hier };
enum class Projection { Orthographic, Perspective };
// What a ray makes of its samples (docs/ALGORITHMS.md section 11): front-to-back compositing of the classified
// samples; the largest, smallest or mean scalar; the first crossing of an iso-value.
enum class Blend { Composite, MIP, MinIP, Average, Iso };
// What shading takes its normals from: central differences of the scalars at every shaded sample, or each voxel's
// gradient stored in 32 bits (render/stored_gradients.h).
enum class Gradients { OnTheFly, Stored };

std::string_view casterName(Caster c);    // "primitive", "pc", "acd", "eacd", "blocks", "hier"
Caster parseCaster(std::string_view name); // throws InputError
std::string_view blendName(Blend b);      // "composite", "mip", "minip", "average", "iso"
Blend parseBlend(std::string_view name);  // throws InputError naming --blend
std::string_view gradientsName(Gradients g);       // "on-the-fly", "stored"
Gradients parseGradients(std::string_view name);  // throws InputError naming --gradients
// Whether the caster leaps through the regions of one classification (PC, ACD, EACD; hier's regions of blocks).
inline bool leapsThroughRegions(Caster c) {
    return c == Caster::PC || c == Caster::ACD || c == Caster::EACD || c == Caster::Hier;
}

struct ViewParams {
    Projection projection = Projection::Orthographic;
    double fovDeg = 30;       // vertical field of view (perspective)
    double azimuthDeg = 0;    // about the up axis
    double elevationDeg = 0;  // about the right axis
    int width = 512, height = 512;
    // VTK's camera calls after the fit, in this order: SetViewUp + OrthogonalizeViewUp (empty: +y turned by the
    // elevation), SetFocalPoint (world; empty: the volume centre), Zoom (> 1 magnifies), then Azimuth by orbitDeg
    // about the view-up: the turn of a view of an orbit.
    std::optional<Vec3d> up{};
    std::optional<Vec3d> centre{};
    double zoom = 1;
    double orbitDeg = 0;
};

// A clipping plane in world units: it keeps the side where dot(normal, x) >= offset.
struct ClipPlane {
    Vec3d normal;
    double offset = 0;
};

// An axis-aligned crop in voxel indices: the voxels lo..hi (inclusive) of each axis are kept.
struct CropBox {
    Vec3i lo, hi;
};

struct RenderSettings {
    Caster caster = Caster::Primitive;
    Blend blend = Blend::Composite;
    double isoValue = 0;       // the iso-surface's scalar (Blend::Iso)
    double stepVoxels = 0.5;   // dt in voxels of the smallest spacing
    double ert = 0.99;         // early ray termination: stop when alpha >= ert
    bool shading = true;       // Phong with one directional light; false: emission-absorption only
    bool trilinear = false;    // trilinear sampling (needs a volume prepared with --trilinear for leaping casters)
    Gradients gradients = Gradients::OnTheFly;
    std::optional<Vec3d> lightDirection;  // world direction towards the light; empty: headlight
    Vec3d background{0, 0, 0};
    long long maxIterationsPerRay = 1 << 24;  // a bug must not hang a render
    // The ray's interval is clipped by these before casting (docs/ALGORITHMS.md section 1): at most
    // device::kMaxClipPlanes planes.
    std::vector<ClipPlane> clipPlanes;
    std::optional<CropBox> crop;
    // Each ray's lattice starts a per-pixel fraction of a step late (shaders/jitter.h): noise instead of wood-grain.
    bool jitter = false;
    // MIP, MinIP and average show their value's TF colour opaque, not at the TF's opacity: with the grey ramp of
    // --window/--level, a grey window (docs/ALGORITHMS.md section 11).
    bool opaqueValues = false;
    // Count each ray's iterations and samples (RenderResult::iterations, samples). Without them the Vulkan casters
    // copy back each pixel's colour alone, half the bytes: on a discrete GPU that copy is a fixed cost of every
    // frame. The CPU reference counts regardless.
    bool rayCounts = true;

    // Whether the render reads each voxel's stored gradient: it shades, from stored gradients.
    bool readsStoredGradients() const { return shading && gradients == Gradients::Stored; }
};

}  // namespace vr
