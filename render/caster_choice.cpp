#include "render/caster_choice.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace vr {
namespace {

// The model: a render costs pixels x (a fixed cost per ray + iterations per pixel x the caster's time per
// iteration), plus the upload of its field, shared by the views. Iterations per pixel come from the ray probe
// volprep stores (probeRays): a count per direction class (axis, plane quadrant, octant) on
// the renderer's own lattice, early ray termination included, so the only constants are the calibration's times.
// They are few on purpose, and the only thing to re-measure when the shader loop or the device changes:
// bench/auto_caster_bench --write-calibration fits them.
constexpr Caster kCasters[] = {Caster::Primitive, Caster::PC, Caster::ACD, Caster::EACD};

// Lavapipe on this project's 2-core machine: least squares of device ms = pixels x (rayNs + iterations x
// iterationNs) over bench/auto_caster_bench's 136 renders (34 rows x 4 casters: the shared datasets and the
// phantoms, T = 0 and 0.02/10, 256x256, 4 views), refitted after the scalars went into 32-bit words and the primitive
// caster shaded out of its loop: ray 44 ns; primitive 12, PC 14, ACD 15, EACD 17 ns an iteration. A leaping
// iteration adds a field fetch, a box exit and the leap's bounds check to the sample; EACD also decodes its extents.
// With them auto picks within 10 % of the fastest fixed caster on all 34 rows (worst 1.02x), the constants before it
// on 28 (worst 1.56x: primitive on the noise phantom, ACD on the teapot where EACD was faster). Those rows'
// scalars are 16 MB or less; beyond, an iteration's time grows as the scalars outgrow the caches:
// bench/auto_caster_bench --growth-sizes on the cranium CT resampled to 17, 134, 268 and 537 MB of scalars
// (primitive renders) gave 5 % more per doubling beyond 17 MB (8 % and 11 % in two runs on a loaded machine before).
// A blocks MIP iteration over a primitive one (bench/blend_bench, 512x512, trilinear, 2 views, device ms per
// iteration of whole renders, the machine quiet, two runs): 2.52-2.62 on the teapot, 2.41-2.45 on the cranium CT,
// 2.23 on the head CT, since MIP starts where the table stops changing what it shows (1.58-2.17 before: the air's
// blocks, cheap to leap, are leapt in fewer iterations, and each ray's fixed cost spreads over fewer). Lavapipe's
// SIMD lanes of 8 rays still run as long as the ray that samples most, so a leap saves less than its iterations
// suggest.
constexpr double kBlocksIterationRatio = 2.4;
// Uploading a field byte (written in place into the image's memory): the bench's median over its rows at the refit
// (0.40-0.45 in three runs before it; 0.58-0.66 when uploads went through a staging copy); a field pays off only
// when it saves more iterations than its bytes cost. The tie: the probe samples a few hundred rays per direction
// class, and the constants are not finer than 5 %.
const CasterCalibration kBuiltIn{44,
                                 {12, 14, 15, 17},
                                 0.14,
                                 0.05,
                                 "llvmpipe (LLVM 15.0.6, 256 bits)",
                                 "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)",
                                 "2026-11-27",
                                 {16.8e6, 0.05},
                                 kBlocksIterationRatio};

// Segmentation (post-classified, trilinear, with normals) and EACD's field in one octant, per voxel, on this
// project's 2-core machine: volrender's own stage times (--stats prepareSeconds) gave 120 ns on the cranium CT (7.1 M
// voxels), 138 ns on a 512x512x1024 CT and 161 ns on a 1024x1024x512 one (both resampled from it, with noise).
// The smallest, so that a borderline case builds the field.
constexpr double kFieldBuildNsPerVoxel = 120;

// The blocks caster's extrema (4 levels) per voxel, built at upload: volrender's MIP upload took 18-22 ms without
// them and 33 ms with them on the cranium CT (7.1 M voxels), 27 and 54-70 ms on the teapot (11.7 M): 2-3.5 ns.
constexpr double kBlockExtremaNsPerVoxel = 3;

// The hier field (block ranges, block regions, the EACD over blocks of 4) per voxel on the same machine: volrender's
// own stage time for one view (one octant) gave 4.4 ns on the cranium CT and 5.0 ns on a 512x512x1024 CT made from
// it while the block ranges were taken from all four levels of the blocks caster's; with their one-level pass
// 3.6-3.7 ns on the shared CTs and 3.2-5.6 ns on the 512x512x1024 CT (the machine loaded by builds). Above the
// one-view figures, so that a borderline case does not build it.
constexpr double kHierBuildNsPerVoxel = 6;
// A one-command render's wait for the device on lavapipe on this project's 2-core machine (volrender's own timings
// from the process's start, head CT): the device opened 36-57 ms in, its pipeline 20-28 ms after that. The smallest,
// so that a borderline case does not build.
constexpr double kDeviceOpenMs = 36;
constexpr double kPipelineMs = 20;

// The part of a build of `buildMs` that the views wait for beyond the device.
double chargedBuildMs(double buildMs, const CasterDemand& d) { return std::max(0.0, buildMs - d.deviceWaitMs); }

// EACD's iterations per ray over hier's (bench/hier_bench: 512 x 512, trilinear, shaded, T_o 0.01, T_a 3, 4-view
// orbits): 0.75 on the teapot, 0.81 on the cranium CT, 0.82 on the head CT, 0.86 on the clinical-size CT.
constexpr double kEACDPerHierIterations = 0.8;

// The probe's counts of caster c; null where the volume had no field for it.
const ProbeCounts* countsOf(const RayProbe& probe, Caster c) {
    auto present = [](const std::optional<ProbeCounts>& counts) { return counts ? &*counts : nullptr; };
    switch (c) {
        case Caster::Primitive: return &probe.primitive;
        case Caster::PC: return present(probe.pc);
        case Caster::ACD: return present(probe.acd);
        case Caster::EACD: return present(probe.eacd);
        case Caster::Blocks: return nullptr;  // a composite render never leaps by blocks
        case Caster::Hier: return nullptr;    // built at render time, never probed by volprep
    }
    return nullptr;
}

double fieldBytesOf(const FieldBytes& bytes, Caster c) {
    switch (c) {
        case Caster::Primitive: return 0;
        case Caster::PC: return double(bytes.pc);
        case Caster::ACD: return double(bytes.acd);
        case Caster::EACD: return double(bytes.eacd);
        case Caster::Blocks: return 0;
        case Caster::Hier: return double(bytes.hier);
    }
    return 0;
}

// Mean over the classes of mask `classes` of a per-class array.
double classMean(const PerDirectionClass& counts, unsigned classes) {
    double sum = 0;
    for (int c = 0; c < kDirectionClasses; ++c)
        if (classes >> c & 1) sum += counts[std::size_t(c)];
    return sum / std::popcount(classes);
}

// Where the volume's bytes raised the iterations' times: by how much, and why; else nothing.
std::string scaleNote(double scale, const CasterDemand& d) {
    if (scale == 1) return {};
    char note[128];
    std::snprintf(note, sizeof note, " (each iteration priced at %.2f x its calibrated time: %.0f MB of scalars)",
                  scale, d.scalarBytes / 1e6);
    return note;
}

struct Estimate {
    Caster caster;
    double iterations;  // per pixel
    double bytes;       // field bytes uploaded for the views
    double cost = 0;
};

}  // namespace

const CasterCalibration& builtInCalibration() { return kBuiltIn; }

double scalarBytesOnDevice(const GridGeometry& grid, ScalarType type) {
    return double(grid.voxels()) * double(scalarBytes(type));
}

double iterationScale(const IterationGrowth& growth, double scalarBytes) {
    if (!(growth.cachedBytes > 0) || !(scalarBytes > growth.cachedBytes)) return 1;
    return 1 + growth.perDoubling * std::log2(scalarBytes / growth.cachedBytes);
}

CasterChoice chooseCaster(const std::optional<RayProbe>& probe, const FieldBytes& bytes, const CasterDemand& d,
                          const CasterCalibration& calibration) {
    const unsigned octants = d.octants & 0xffu;
    const unsigned anyClass = (1u << kDirectionClasses) - 1 - (1u << kNoDirection);
    if (d.views.empty() || std::any_of(d.views.begin(), d.views.end(), [&](unsigned v) { return !v || v & ~anyClass; }))
        throw std::invalid_argument("chooseCaster: no views, or a view without direction classes");
    if (!probe || !(probe->stepVoxels > 0) || !octants)
        return {Caster::Primitive, "the prepared file has no ray probe (prepared by an older volprep, or rays too "
                                   "long to probe): primitive reads no field"};

    // Iterations that leapt several samples do not depend on the step; those that took one sample (small regions,
    // opaque tissue, the primitive caster) grow as the step shrinks. No caster takes more than primitive's.
    const double stepScale = probe->stepVoxels / std::max(d.stepVoxels, 1e-6);
    std::vector<Estimate> estimates;
    std::vector<double> primitivePerView;
    for (const Caster c : kCasters) {  // primitive first
        const ProbeCounts* counts = countsOf(*probe, c);
        const double fieldBytes = fieldBytesOf(bytes, c);
        if (!counts || (c != Caster::Primitive && fieldBytes <= 0)) continue;
        double iterations = 0;  // per pixel, mean over the views
        for (std::size_t v = 0; v < d.views.size(); ++v) {
            const double perView =
                classMean(counts->leaps, d.views[v]) + classMean(counts->singleSamples, d.views[v]) * stepScale;
            if (c == Caster::Primitive) primitivePerView.push_back(perView);
            iterations += std::min(perView, primitivePerView[v]) / double(d.views.size());
        }
        // PC has one field for every direction; ACD and EACD upload the octants the view's rays have.
        const double uploaded = c == Caster::PC ? fieldBytes : fieldBytes * std::popcount(octants) / kOctants;
        estimates.push_back({c, iterations, uploaded});
    }
    const double views = double(d.views.size());
    const double scale = iterationScale(calibration.growth, d.scalarBytes);
    for (Estimate& e : estimates) {
        const double iterationNs = calibration.iterationNs[std::size_t(e.caster)] * scale;
        e.cost = double(d.pixels) * (calibration.rayNs + e.iterations * iterationNs) +
                 e.bytes * calibration.uploadNsPerByte / views;
    }

    const Estimate* best = &*std::min_element(estimates.begin(), estimates.end(),
                                              [](const Estimate& a, const Estimate& b) { return a.cost < b.cost; });
    const double tie = best->cost * (1 + calibration.tie);
    for (const Estimate& e : estimates)
        if (e.cost <= tie && e.bytes < best->bytes) best = &e;

    // Every candidate's iterations per pixel and cost relative to the primitive caster's, so a choice can be checked.
    std::string reason = "estimated iterations per pixel and cost relative to primitive (" +
                         std::to_string(d.views.size()) + " view(s) sharing the upload):";
    for (const Estimate& e : estimates) {
        char part[96];
        std::snprintf(part, sizeof part, " %s %.1f, %.3f;", casterName(e.caster).data(), e.iterations,
                      e.cost / estimates.front().cost);
        reason += part;
    }
    reason.pop_back();
    reason += scaleNote(scale, d);
    return {best->caster, reason};
}

namespace {

// Milliseconds of the views at `iterations` per pixel, each iteration `iterationNs` as calibrated (scaled here for
// the volume's bytes).
double viewsMs(const CasterDemand& d, double iterations, double iterationNs, const CasterCalibration& calibration) {
    const double scale = iterationScale(calibration.growth, d.scalarBytes);
    return double(d.views.size()) * double(d.pixels) * (calibration.rayNs + iterations * iterationNs * scale) * 1e-6;
}

}  // namespace

double deviceWaitMs(double sinceOpeningMs, bool open) {
    return (open ? 0 : std::max(0.0, kDeviceOpenMs - sinceOpeningMs)) + kPipelineMs;
}

bool hierMayPay(double primitiveIterations, const CasterDemand& d, std::size_t voxels,
                const CasterCalibration& calibration) {
    return viewsMs(d, primitiveIterations, calibration.iterationNs[0], calibration) >
           double(voxels) * kHierBuildNsPerVoxel * 1e-6;
}

CasterChoice chooseBeforeBuilding(const ProbedIterations& it, const CasterDemand& d, std::size_t voxels,
                                  const CasterCalibration& calibration) {
    const double leapNs = calibration.iterationNs[std::size_t(Caster::EACD)];
    const double primitiveMs = viewsMs(d, it.primitive, calibration.iterationNs[0], calibration);
    const double buildMs = double(voxels) * kFieldBuildNsPerVoxel * 1e-6;
    const double eacdMs =
        it.hier ? chargedBuildMs(buildMs, d) + viewsMs(d, *it.hier * kEACDPerHierIterations, leapNs, calibration)
                : buildMs;
    const double hierMs = it.hier ? viewsMs(d, *it.hier, leapNs, calibration) : primitiveMs;
    char reason[448];
    int at = std::snprintf(reason, sizeof reason,
                           "%zu view(s) cast without a field take an estimated %.0f ms (%.1f iterations per pixel); ",
                           d.views.size(), primitiveMs, it.primitive);
    if (it.hier)
        at += std::snprintf(reason + at, sizeof reason - std::size_t(at),
                            "with the hier field, built, %.0f ms (%.1f iterations per pixel); ", hierMs, *it.hier);
    at += std::snprintf(reason + at, sizeof reason - std::size_t(at), "EACD's field alone would take %.0f ms to build",
                        buildMs);
    if (it.hier && d.deviceWaitMs > 0)
        at += std::snprintf(reason + at, sizeof reason - std::size_t(at),
                            " (%.0f ms of it while the device gets ready)", std::min(buildMs, d.deviceWaitMs));
    std::snprintf(reason + at, sizeof reason - std::size_t(at), "%s",
                  scaleNote(iterationScale(calibration.growth, d.scalarBytes), d).c_str());
    const Caster best = primitiveMs <= std::min(hierMs, eacdMs) ? Caster::Primitive
                        : hierMs <= eacdMs                      ? Caster::Hier
                                                                : Caster::EACD;
    return {best, reason};
}

CasterChoice chooseBlendCaster(double primitiveIterations, double blocksIterations, const CasterDemand& d,
                               std::size_t voxels, const CasterCalibration& calibration) {
    const double ratio =
        calibration.blocksIterationRatio > 0 ? calibration.blocksIterationRatio : kBlocksIterationRatio;
    const double primitiveNs = calibration.iterationNs[std::size_t(Caster::Primitive)];
    const double primitiveMs = viewsMs(d, primitiveIterations, primitiveNs, calibration);
    const double buildMs = double(voxels) * kBlockExtremaNsPerVoxel * 1e-6;
    const double blocksMs = viewsMs(d, blocksIterations, primitiveNs * ratio, calibration) + buildMs;
    char reason[256];
    std::snprintf(reason, sizeof reason,
                  "%zu view(s) cast without leaping take an estimated %.0f ms (%.1f iterations per pixel), by the "
                  "blocks' extrema %.0f ms (%.1f iterations per pixel, each %.2f times as dear)",
                  d.views.size(), primitiveMs, primitiveIterations, blocksMs, blocksIterations, ratio);
    return {blocksMs < primitiveMs * (1 - calibration.tie) ? Caster::Blocks : Caster::Primitive, reason};
}

}  // namespace vr
