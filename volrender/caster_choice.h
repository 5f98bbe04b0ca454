// --caster auto: which caster to render a view with, chosen among the fields a prepared file holds from the
// statistics volprep stored in it (preparedStatistics: voxels, regions, mean leap per field and octant, bytes).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "core/vec3.h"
#include "volrender/render_settings.h"

namespace vr {

// The view(s) to render, as far as the choice depends on them.
struct CasterDemand {
    Projection projection = Projection::Orthographic;
    Vec3d direction{0, 0, -1};  // the camera's forward direction (world; the central ray of a perspective view)
    unsigned octants = 1;       // ray octants the views have (viewOctants): the ACD/EACD octants uploaded
    long long pixels = 512 * 512;
    double stepVoxels = 0.5;
    int views = 1;              // renders that share one upload of the field
};

struct CasterChoice {
    Caster caster = Caster::Primitive;
    std::string reason;  // one line: each candidate's estimated leap and relative cost
};

// Estimates each available caster's cost as pixels x ray length / mean leap x a per-iteration weight, plus the
// upload of its field (bytes, per octant uploaded) shared by the views, and returns the cheapest; when a leaner
// caster is within a few percent of it, the one with less to upload. Statistics without leap means or bytes (an
// old or foreign file) give the primitive caster, which needs no field.
CasterChoice chooseCaster(const nlohmann::json& statistics, const CasterDemand& demand);

}  // namespace vr
