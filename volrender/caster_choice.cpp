#include "volrender/caster_choice.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/distance_fields.h"

namespace vr {
using json = nlohmann::json;

namespace {

// Cost of one loop iteration relative to the primitive caster's sample, measured on lavapipe
// (bench/auto_caster_bench: the checkerboard and noise phantoms, where every voxel is a region and every caster
// but PC takes about one iteration per voxel): a leaping caster integrates and shades a span once, in closed
// form, where the primitive caster does so at every sample; PC pays its field fetch on top of sampling where its
// radius is 0; EACD's extents cost about 10 % more per iteration than ACD's one byte.
double iterationWeight(Caster c) {
    switch (c) {
        case Caster::Primitive: return 1.0;
        case Caster::PC: return 1.2;
        case Caster::ACD: return 0.3;
        case Caster::EACD: return 0.33;
    }
    return 1.0;
}

// Uploading this many bytes costs about one primitive sample on lavapipe (~100-200 ns per sample on 2 cores
// against ~1 ns per byte copied): a field pays off only when it saves more work than its bytes.
constexpr double kBytesPerIteration = 128;
// Casters whose estimates lie within this fraction of the cheapest are a tie: the one with less to upload wins
// (the estimate from mean leaps is not finer than this).
constexpr double kTie = 0.05;

double number(const json& j, const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

// A uniform ray meets voxels in proportion to how long it stays in them, so a mean over voxels overstates its
// mean leap; the estimates below are still ordered as the casters' leaps are (EACD >= ACD per axis).
struct Estimate {
    Caster caster;
    double leap;   // voxels per iteration
    double bytes;  // field bytes uploaded for the views
    double cost = 0;
};

// How far a ray along unit `d` goes from a point at the middle of a voxel's face to the far side of a box of
// extents e (voxels) starting at that voxel: the nearest exit, min over axes of (e_a - 1/2) / |d_a|.
double boxLeap(const std::array<double, 3>& e, const Vec3d& d) {
    double leap = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
        if (std::abs(d[a]) > 1e-9) leap = std::min(leap, (e[a] - 0.5) / std::abs(d[a]));
    return std::isfinite(leap) ? leap : 0;
}

// Mean leap of one caster over the demanded octants; 0 when the file lacks the field's statistics.
double meanLeap(const json& leaps, Caster c, const CasterDemand& d) {
    const Vec3d dir = d.direction / std::max(length(d.direction), 1e-300);
    if (c == Caster::PC) {  // a cube of radius r centred on the voxel: r + 1/2 from its middle
        const double r = number(leaps, "pcMeanRadius");
        return r > 0 ? boxLeap({r + 1, r + 1, r + 1}, dir) : 0;
    }
    const char* key = c == Caster::ACD ? "acdMeanEdge" : "eacdMeanExtent";
    const auto field = leaps.find(key);
    if (field == leaps.end() || !field->is_array() || field->size() != kOctants) return 0;
    double sum = 0;
    int n = 0;
    for (int o = 0; o < kOctants; ++o) {
        if (!(d.octants >> o & 1)) continue;
        const json& v = (*field)[std::size_t(o)];
        if (c == Caster::ACD && v.is_number()) {
            const double k = v.get<double>();
            sum += boxLeap({k, k, k}, dir);
        } else if (c == Caster::EACD && v.is_array() && v.size() == 3) {
            sum += boxLeap({v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}, dir);
        }
        ++n;
    }
    return n ? sum / n : 0;
}

}  // namespace

CasterChoice chooseCaster(const json& s, const CasterDemand& d) {
    const json leaps = s.contains("leaps") ? s["leaps"] : json::object();
    const json bytes = s.contains("bytes") ? s["bytes"] : json::object();
    const double voxels = number(s, "voxels");
    if (voxels <= 0 || !d.octants)
        return {Caster::Primitive, "the prepared file has no statistics to choose from: primitive reads no field"};

    // Ray length in voxels: the mean chord of a cube of this many voxels is about its edge.
    const double rayVoxels = std::cbrt(voxels);
    const double step = std::max(d.stepVoxels, 1e-6);
    const int octants = std::popcount(d.octants & 0xffu);
    const double views = std::max(d.views, 1);

    std::vector<Estimate> estimates{{Caster::Primitive, step, 0}};
    const std::pair<Caster, const char*> fields[] = {{Caster::PC, "pc"}, {Caster::ACD, "acd"}, {Caster::EACD, "eacd"}};
    for (const auto& [caster, name] : fields) {
        const double fieldBytes = number(bytes, name);
        const double leap = meanLeap(leaps, caster, d);
        if (fieldBytes <= 0 || leap <= 0) continue;  // not in the file
        // PC has one field for every direction; ACD and EACD upload the octants the view's rays have.
        const double uploaded = caster == Caster::PC ? fieldBytes : fieldBytes * octants / kOctants;
        estimates.push_back({caster, std::max(leap, step), uploaded});
    }
    for (Estimate& e : estimates)
        e.cost = double(d.pixels) * rayVoxels / e.leap * iterationWeight(e.caster) +
                 e.bytes / kBytesPerIteration / views;

    const Estimate* best = &*std::min_element(estimates.begin(), estimates.end(),
                                              [](const Estimate& a, const Estimate& b) { return a.cost < b.cost; });
    const double tie = best->cost * (1 + kTie);
    for (const Estimate& e : estimates)
        if (e.cost <= tie && e.bytes < best->bytes) best = &e;

    // Every candidate's leap and cost relative to the primitive caster's, so that a choice can be checked.
    std::string reason = "estimated voxels per iteration and cost relative to primitive (with " +
                         std::to_string(d.views) + " view(s) sharing the upload):";
    for (const Estimate& e : estimates) {
        char part[96];
        std::snprintf(part, sizeof part, " %s %.2f, %.3f;", std::string(casterName(e.caster)).c_str(), e.leap,
                      e.cost / estimates.front().cost);
        reason += part;
    }
    reason.pop_back();
    return {best->caster, reason};
}

}  // namespace vr
