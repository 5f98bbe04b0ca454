// --caster auto: which caster to render a view with, chosen among the fields a prepared file holds from the
// statistics volprep stored in it (preparedStatistics: the ray probe's iterations per caster and
// direction class, bytes).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/direction_class.h"
#include "render/render_settings.h"

namespace vr {

// The views to render, which share one upload of the field.
struct CasterDemand {
    unsigned octants = 0;          // ray octants the views have (viewOctants): the ACD / EACD octants uploaded
    std::vector<unsigned> views;   // per view, the ray probe's direction classes its rays fall in
    long long pixels = 512 * 512;  // per view
    double stepVoxels = 0.5;

    void addView(const Camera& camera) {
        octants |= viewOctants(camera);
        views.push_back(viewDirectionClasses(camera));
    }
};

struct CasterChoice {
    Caster caster = Caster::Primitive;
    std::string reason;  // one line: each candidate's estimated iterations per pixel and relative cost
};

// Estimates each available caster's time as pixels x (a cost per ray + iterations per pixel x its time per
// iteration) per view, the iterations from the file's ray probe for the view's direction classes (rescaled to the
// step), plus the upload of its field (bytes, per octant uploaded) shared by the views, and returns the cheapest; when a leaner
// caster is within a few percent of it, the one with less to upload. Statistics without a ray probe (an old or
// foreign file) give the primitive caster, which needs no field, and a reason that says so.
CasterChoice chooseCaster(const nlohmann::json& statistics, const CasterDemand& demand);

// The model's device time of one loop iteration of a caster (measured: see caster_choice.cpp).
double iterationNanoseconds(Caster caster);

}  // namespace vr
