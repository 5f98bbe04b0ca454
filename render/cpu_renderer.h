// The CPU reference renderer: the casters of docs/ALGORITHMS.md section 5 and the blends of section 11 in double
// precision.
#pragma once
#include "render/camera.h"
#include "core/prepared_volume.h"
#include "render/render_result.h"

namespace vr {

// Throws InputError when the caster needs a field (or shading needs normals) the prepared volume lacks, and
// std::runtime_error when a ray hits the iteration cap (a bug, reported rather than hung).
RenderResult renderCpu(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings);

}  // namespace vr
