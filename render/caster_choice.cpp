#include "render/caster_choice.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "core/distance_fields.h"

namespace vr {
using json = nlohmann::json;

namespace {

// The model: a render costs pixels x (a fixed cost per ray + iterations per pixel x the caster's time per
// iteration), plus the upload of its field, shared by the views. Iterations per pixel come from the ray probe
// volprep stores (rayProbe in preparedStatistics): a count per direction class (axis, plane quadrant, octant) on
// the renderer's own lattice, early ray termination included, so the only constants are the times below. They are
// few on purpose, and the only thing to re-measure when the shader loop or the device changes:
// bench/auto_caster_bench prints the data to fit them.
struct CasterCost {
    Caster caster;
    const char* name;    // in the statistics' rayProbe and bytes
    double iterationNs;  // device time of one loop iteration
};
// Lavapipe on this project's 2-core machine: least squares of device ms = pixels x (kRayNs + iterations x
// iterationNs) over bench/auto_caster_bench's 136 renders (34 rows x 4 casters: the shared datasets and the
// phantoms, T = 0 and 0.02/10, 256x256, 4 views). A leaping iteration adds a field fetch, a box exit and the
// leap's bounds check to the sample; EACD also decodes its extents. Kept after later shader changes made every
// iteration cheaper (primitive 2.8x, EACD 1.2x): they still pick within 10 % on 33 of 34 rows, where a fit to
// the faster shaders (ray 27; 5, 9, 11, 13) picks so on 29-30. An iteration's time grows with the
// volume (primitive: 3 ns on 2 MB of classified voxels, 10 ns on 268 MB), which these constants do not model.
constexpr double kRayNs = 38;
constexpr std::array<CasterCost, 4> kCasters{{{Caster::Primitive, "primitive", 11},
                                              {Caster::PC, "pc", 15},
                                              {Caster::ACD, "acd", 17},
                                              {Caster::EACD, "eacd", 20}}};
// Wall time to upload one byte of a field (lavapipe: written in place into the image's memory): a field pays off
// only when it saves more iterations than its bytes cost. The bench's median over its rows (0.40-0.45 in three
// runs; 0.58-0.66 when uploads went through a staging copy).
constexpr double kUploadNsPerByte = 0.44;
// Casters whose estimates lie within this fraction of the cheapest are a tie, which the one with less to upload
// wins: the probe samples a few hundred rays per direction class, and the constants above are not finer than this.
constexpr double kTie = 0.05;

double number(const json& j, const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

// A probe's per-class array (kDirectionClasses numbers); empty when missing or malformed (an older file's
// per-octant arrays included).
std::vector<double> classCounts(const json& probe, const char* key) {
    const auto it = probe.find(key);
    if (it == probe.end() || !it->is_array() || it->size() != kDirectionClasses) return {};
    std::vector<double> out;
    for (const json& x : *it) {
        if (!x.is_number()) return {};
        out.push_back(x.get<double>());
    }
    return out;
}

// Mean over the classes of mask `classes` of a per-class array.
double classMean(const std::vector<double>& counts, unsigned classes) {
    double sum = 0;
    for (int c = 0; c < kDirectionClasses; ++c)
        if (classes >> c & 1) sum += counts[std::size_t(c)];
    return sum / std::popcount(classes);
}

struct Estimate {
    const CasterCost* caster;
    double iterations;  // per pixel
    double bytes;       // field bytes uploaded for the views
    double cost = 0;
};

}  // namespace

double iterationNanoseconds(Caster caster) {
    for (const CasterCost& c : kCasters)
        if (c.caster == caster) return c.iterationNs;
    return kCasters.front().iterationNs;
}

CasterChoice chooseCaster(const json& s, const CasterDemand& d) {
    const json probe = s.is_object() && s.contains("rayProbe") ? s["rayProbe"] : json::object();
    const json bytes = s.is_object() && s.contains("bytes") ? s["bytes"] : json::object();
    const json casters = probe.contains("casters") ? probe["casters"] : json::object();
    const double probeStep = number(probe, "stepVoxels");
    const unsigned octants = d.octants & 0xffu;
    const unsigned anyClass = (1u << kDirectionClasses) - 1 - (1u << kNoDirection);
    if (d.views.empty() || std::any_of(d.views.begin(), d.views.end(), [&](unsigned v) { return !v || v & ~anyClass; }))
        throw std::invalid_argument("chooseCaster: no views, or a view without direction classes");
    if (probeStep <= 0 || !casters.contains("primitive") || !octants)
        return {Caster::Primitive, "the prepared file has no ray probe (prepared by an older volprep, or rays too "
                                   "long to probe): primitive reads no field"};

    // Iterations that leapt several samples do not depend on the step; those that took one sample (small regions,
    // opaque tissue, the primitive caster) grow as the step shrinks. No caster takes more than primitive's.
    const double stepScale = probeStep / std::max(d.stepVoxels, 1e-6);
    std::vector<Estimate> estimates;
    std::vector<double> primitivePerView;
    for (const CasterCost& c : kCasters) {
        const json counts = casters.contains(c.name) ? casters[c.name] : json();
        if (!counts.is_object() || (c.caster != Caster::Primitive && primitivePerView.empty())) continue;
        const std::vector<double> leaps = classCounts(counts, "leaps"), singles = classCounts(counts, "singleSamples");
        const double fieldBytes = number(bytes, c.name);
        if (leaps.empty() || singles.empty() || (c.caster != Caster::Primitive && fieldBytes <= 0)) continue;
        double iterations = 0;  // per pixel, mean over the views
        for (std::size_t v = 0; v < d.views.size(); ++v) {
            double perView = classMean(leaps, d.views[v]) + classMean(singles, d.views[v]) * stepScale;
            if (c.caster == Caster::Primitive) primitivePerView.push_back(perView);
            iterations += std::min(perView, primitivePerView[v]) / double(d.views.size());
        }
        // PC has one field for every direction; ACD and EACD upload the octants the view's rays have.
        const double uploaded = c.caster == Caster::PC ? fieldBytes : fieldBytes * std::popcount(octants) / kOctants;
        estimates.push_back({&c, iterations, uploaded});
    }
    if (estimates.empty() || estimates.front().caster->caster != Caster::Primitive)
        return {Caster::Primitive, "the prepared file's ray probe has no primitive count: primitive reads no field"};
    const double views = double(d.views.size());
    for (Estimate& e : estimates)
        e.cost = double(d.pixels) * (kRayNs + e.iterations * e.caster->iterationNs) + e.bytes * kUploadNsPerByte / views;

    const Estimate* best = &*std::min_element(estimates.begin(), estimates.end(),
                                              [](const Estimate& a, const Estimate& b) { return a.cost < b.cost; });
    const double tie = best->cost * (1 + kTie);
    for (const Estimate& e : estimates)
        if (e.cost <= tie && e.bytes < best->bytes) best = &e;

    // Every candidate's iterations per pixel and cost relative to the primitive caster's, so a choice can be checked.
    std::string reason = "estimated iterations per pixel and cost relative to primitive (" + std::to_string(d.views.size()) +
                         " view(s) sharing the upload):";
    for (const Estimate& e : estimates) {
        char part[96];
        std::snprintf(part, sizeof part, " %s %.1f, %.3f;", e.caster->name, e.iterations,
                      e.cost / estimates.front().cost);
        reason += part;
    }
    reason.pop_back();
    return {best->caster->caster, reason};
}

}  // namespace vr
