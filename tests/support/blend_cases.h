// The blends other than composite (docs/ALGORITHMS.md section 11), as the CPU reference and the Vulkan casters both
// face them: the blocks caster against the primitive one, each blend against a brute force written here, an
// axis-aligned MIP against the maximum of each voxel column, and MIP and MinIP from opposite sides.
#pragma once
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

// How far one renderer's images may lie apart where they should be equal: the CPU reference's double sums of
// average agree to rounding, the device's float pairs to about 1e-7.
struct BlendTolerance {
    double equal = 1e-12;
};

// At views along the axes, diagonal and in perspective, nearest and trilinear: the blocks caster renders the
// primitive caster's image with no more iterations on any pixel, and fewer in all for MIP and the iso-surface.
CaseCount blocksEqualPrimitive(const RenderFn& render, const BlendTolerance& tolerance);

// Every blend against a brute force that samples each ray's whole lattice: MIP, MinIP and average show the TF
// colour and opacity of the largest, smallest and mean scalar; the unshaded iso-surface its TF colour where a ray
// crosses the iso-value, after as many samples as the brute force takes to the crossing. At most `allowedShare` of
// the pixels may differ (by more than 1e-4): the device's float positions put a sample within about 1e-5 voxels of
// a voxel face now and then in the neighbouring voxel.
CaseCount blendsMatchBruteForce(const RenderFn& render, double allowedShare);

// An orthographic MIP along each axis, nearest and trilinear, with a ray through the centre of every voxel column:
// each pixel shows the largest scalar of its column.
CaseCount axisMipIsColumnMaximum(const RenderFn& render);

// MIP and MinIP along an axis from either side, the second camera's right the first's left: mirror images.
CaseCount oppositeViewsMirror(const RenderFn& render);

}  // namespace vr::test
