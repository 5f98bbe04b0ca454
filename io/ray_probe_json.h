// The ray probe in the prepared file's header (metadata.statistics.rayProbe, docs/PREPARED_FORMAT.md).
#pragma once
#include <nlohmann/json.hpp>
#include <optional>

#include "core/ray_probe.h"

namespace vr {

nlohmann::json rayProbeJson(const RayProbe& probe);

// None for a probe of another form (an older volprep's: per-octant counts, no views) or without primitive counts;
// a leaping caster whose counts are not 27 numbers each is left out. Such files stay readable: --caster auto then
// chooses among what is left, or takes the primitive caster.
std::optional<RayProbe> rayProbeFromJson(const nlohmann::json& probe);

}  // namespace vr
