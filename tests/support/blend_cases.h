// The blends other than composite (docs/ALGORITHMS.md section 11), as the CPU reference and the Vulkan casters both
// face them: the blocks caster against the primitive one, each blend against a brute force written here, an
// axis-aligned MIP against the maximum of each voxel column, and MIP and MinIP from opposite sides.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "support/render_cases.h"

namespace vr::test {

inline constexpr Blend kScalarBlends[] = {Blend::MIP, Blend::MinIP, Blend::Average, Blend::Iso};

struct BlendVolume {
    std::string name;
    PreparedVolume prepared;
    double isoValue;  // between its scalars' extremes, on no voxel's value
};

// Phantoms with air and structure, noise, and a central block of a real CT, prepared without fields (the blocks
// caster builds its extrema from the scalars).
const std::vector<BlendVolume>& blendVolumes();

// Settings of a blend render: unshaded but for the iso-surface, at step 0.5 voxel.
RenderSettings blendSettings(Blend blend, Caster caster, bool trilinear, double isoValue);

// What a renderer is asked: how far its images may lie apart where they should be equal (images hold float; the
// CPU reference's double sums of average agree to rounding, the device's float pairs to about 1e-7; the device
// classifies in float), and how many of the views (a diagonal, a perspective, then views along the axes and another
// diagonal) it renders (the device compiles a pipeline per variant).
struct BlendCaseOptions {
    double equal = 1e-7;
    std::size_t views = 6;
};

// At those views, nearest and trilinear: the blocks caster renders the primitive caster's image with no more
// iterations on any pixel (but MIP's and MinIP's probe samples), and fewer in all for MIP and the iso-surface where
// there is air.
CaseCount blocksEqualPrimitive(const RenderFn& render, const BlendCaseOptions& options);

// Every blend against a brute force that samples each ray's whole lattice: MIP, MinIP and average show the TF
// colour and opacity of the largest, smallest and mean scalar; the unshaded iso-surface its TF colour where a ray
// crosses the iso-value, after as many samples as the brute force takes to the crossing. At most `allowedShare` of
// the pixels may differ (by more than 1e-4): the device's float positions put a sample within about 1e-5 voxels of
// a voxel face now and then in the neighbouring voxel.
CaseCount blendsMatchBruteForce(const RenderFn& render, double allowedShare);

// An orthographic MIP along each axis, nearest and trilinear, with a ray through the centre of every voxel column:
// each pixel shows the largest scalar of its column (within options.equal).
CaseCount axisMipIsColumnMaximum(const RenderFn& render, const BlendCaseOptions& options);

// MIP and MinIP along each axis from either side, the second camera's right the first's left: mirror images.
CaseCount oppositeViewsMirror(const RenderFn& render, const BlendCaseOptions& options);

// MIP and MinIP through the grey ramp of --window/--level along z: with opaqueValues the window's grey, linear in
// the value and opaque; without, that grey at the ramp's opacity (its square over black).
CaseCount greyWindowIsLinear(const RenderFn& render, const BlendCaseOptions& options);

}  // namespace vr::test
