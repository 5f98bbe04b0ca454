// The checks every renderer (CPU reference or Vulkan) makes before casting a ray: one place, one message each.
#pragma once
#include "core/prepared_volume.h"
#include "render_settings.h"

namespace vr {

// Throws InputError when the settings are unusable (step, ERT, light) or the prepared volume lacks what the
// caster needs (normals for shading, the caster's field, border regions for trilinear leaping).
void checkRenderInputs(const PreparedVolume& prepared, const RenderSettings& settings);

}  // namespace vr
