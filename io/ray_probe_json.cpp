#include "io/ray_probe_json.h"

#include <utility>

namespace vr {
using json = nlohmann::json;

namespace {

// The leaping casters' counts under their names in "casters" (the primitive caster's are always there).
constexpr std::pair<const char*, std::optional<ProbeCounts> RayProbe::*> kLeapingCounts[] = {
    {"pc", &RayProbe::pc}, {"acd", &RayProbe::acd}, {"eacd", &RayProbe::eacd}};

json countsJson(const ProbeCounts& c) { return {{"leaps", c.leaps}, {"singleSamples", c.singleSamples}}; }

std::optional<PerDirectionClass> perClass(const json& counts, const char* key) {
    const auto it = counts.find(key);
    if (it == counts.end() || !it->is_array() || it->size() != kProbeDirectionClasses) return std::nullopt;
    PerDirectionClass out{};
    for (std::size_t c = 0; c < out.size(); ++c) {
        if (!(*it)[c].is_number()) return std::nullopt;
        out[c] = (*it)[c].get<double>();
    }
    return out;
}

std::optional<ProbeCounts> countsFromJson(const json& casters, const char* name) {
    const auto it = casters.find(name);
    if (it == casters.end() || !it->is_object()) return std::nullopt;
    const auto leaps = perClass(*it, "leaps"), singles = perClass(*it, "singleSamples");
    if (!leaps || !singles) return std::nullopt;
    return ProbeCounts{*leaps, *singles};
}

// A number under `key`, into `to`; false when there is none.
template <typename T>
bool numberAt(const json& j, const char* key, T& to) {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number()) return false;
    to = it->get<T>();
    return true;
}

}  // namespace

json rayProbeJson(const RayProbe& p) {
    json casters{{"primitive", countsJson(p.primitive)}};
    for (const auto& [name, counts] : kLeapingCounts)
        if (p.*counts) casters[name] = countsJson(*(p.*counts));
    return {{"stepVoxels", p.stepVoxels},
            {"ert", p.ert},
            {"views", {{"octant", p.octantViews}, {"quadrant", p.quadrantViews}, {"axis", p.axisViews}}},
            {"casters", casters}};
}

std::optional<RayProbe> rayProbeFromJson(const json& j) {
    RayProbe p;
    const json views = j.is_object() ? j.value("views", json()) : json();
    const json casters = j.is_object() ? j.value("casters", json()) : json();
    if (!views.is_object() || !casters.is_object() || !numberAt(j, "stepVoxels", p.stepVoxels) ||
        !numberAt(j, "ert", p.ert) || !numberAt(views, "octant", p.octantViews) ||
        !numberAt(views, "quadrant", p.quadrantViews) || !numberAt(views, "axis", p.axisViews))
        return std::nullopt;
    const std::optional<ProbeCounts> primitive = countsFromJson(casters, "primitive");
    if (!primitive) return std::nullopt;
    p.primitive = *primitive;
    for (const auto& [name, counts] : kLeapingCounts) p.*counts = countsFromJson(casters, name);
    return p;
}

}  // namespace vr
