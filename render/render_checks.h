// The checks every renderer (CPU reference or Vulkan) makes before casting a ray: one place, one message each.
#pragma once
#include "core/prepared_volume.h"
#include "render/render_settings.h"

namespace vr {

// Throws InputError when the settings are unusable (step, ERT, light) or the prepared volume lacks what the
// caster needs (scalars and a transfer table that fit, the caster's field, and what checkRenderSettings asks).
void checkRenderInputs(const PreparedVolume& prepared, const RenderSettings& settings);

// Throws InputError naming --step when a ray across `grid` takes more lattice samples than the iteration cap
// (settings.maxIterationsPerRay, or the default cap where that is lower): such a step is refused up front instead
// of failing the render with the cap's error, which is meant for runaway casters.
void requireSamplesWithinCap(const GridGeometry& grid, const RenderSettings& settings);

// Throws InputError naming --step (not a positive finite number of voxels) or --ert (outside (0, 1]). Needs no
// volume: volrender checks them before reading one.
void checkStepAndTermination(double stepVoxels, double ert);

// Throws InputError naming --clip: more than device::kMaxClipPlanes planes, a zero or non-finite normal, a
// non-finite offset. Needs no volume.
void checkClipPlanes(const std::vector<ClipPlane>& planes);
// Throws InputError naming --crop: a crop box that is empty or reaches outside the grid's voxels.
void checkCrop(const GridGeometry& grid, const CropBox& crop);

// Throws InputError when the caster does not leap in a way the blend allows (PC, ACD and EACD composite only, blocks
// any other blend) or the iso-value is not finite.
void checkBlend(const RenderSettings& settings);

// Throws InputError naming --labels and --blend where a volume with a label map (`labelled`) is rendered with a
// blend other than composite: MIP, MinIP, average and the iso-surface follow the scalar alone.
void checkLabelledBlend(bool labelled, const RenderSettings& settings);

// The part of checkRenderInputs that needs no voxel data (step, ERT, light, clipping, blend; trilinear leaping on
// regions made for it, shaded leaping on regions made with normals): what a render of a volume already on a device
// checks.
void checkRenderSettings(const GridGeometry& grid, const SegmentationParams& segmentation,
                         const RenderSettings& settings);

}  // namespace vr
