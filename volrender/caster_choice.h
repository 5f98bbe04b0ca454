// --caster auto: which caster to render a view with, chosen among the fields a prepared file holds from the
// statistics volprep stored in it (preparedStatistics: the ray probe's iterations per caster and octant, bytes).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "volrender/render_settings.h"

namespace vr {

// The view(s) to render. The probe's counts already average the directions within an octant, so the octants
// the views' rays have say all the estimate needs of their directions.
struct CasterDemand {
    unsigned octants = 1;       // ray octants the views have (viewOctants): the probe's octants, and the
                                // ACD / EACD octants uploaded
    long long pixels = 512 * 512;
    double stepVoxels = 0.5;
    int views = 1;              // renders that share one upload of the field
};

struct CasterChoice {
    Caster caster = Caster::Primitive;
    std::string reason;  // one line: each candidate's estimated iterations per pixel and relative cost
};

// Estimates each available caster's time as pixels x (a cost per ray + iterations per pixel x its time per
// iteration), the iterations from the file's ray probe over the demanded octants (rescaled to the step), plus the
// upload of its field (bytes, per octant uploaded) shared by the views, and returns the cheapest; when a leaner
// caster is within a few percent of it, the one with less to upload. Statistics without a ray probe (an old or
// foreign file) give the primitive caster, which needs no field, and a reason that says so.
CasterChoice chooseCaster(const nlohmann::json& statistics, const CasterDemand& demand);

// The model's device time of one loop iteration of a caster (measured: see caster_choice.cpp).
double iterationNanoseconds(Caster caster);

}  // namespace vr
