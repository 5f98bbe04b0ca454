// The ray probe behind --caster auto (render/caster_choice.h), stored in the prepared file's statistics.
#pragma once
#include <nlohmann/json.hpp>

#include "core/prepared_volume.h"

namespace vr {

// Per direction class (render/direction_class.h: the 8 octants, 12 plane quadrants and 6 axes) and per caster
// the fields allow, the mean loop iterations per pixel of the CPU reference renderer (the casters' own loop:
// lattice, leaps, early ray termination; nearest sampling, unshaded) over small orthographic views along
// directions of the class, split into iterations that leap several samples ("leaps", independent of the step)
// and single samples ("singleSamples", which grow as the step shrinks). Form: {"stepVoxels", "ert", "views":
// {"octant", "quadrant", "axis"}, "casters": {NAME: {"leaps": [27], "singleSamples": [27]}}}, indexed by class
// (entry 13 unused, 0); null for a volume whose rays are too long to probe (spacings far apart: more than 2^17
// samples across).
nlohmann::json rayProbe(const PreparedVolume& prepared);

}  // namespace vr
