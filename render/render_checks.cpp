#include "render/render_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/errors.h"
#include "render/ray_setup.h"

namespace vr {

void requireSamplesWithinCap(const GridGeometry& grid, const RenderSettings& s) {
    // The primitive caster takes one iteration per sample, so a lattice longer than the cap would fail a correct
    // render with the cap's "a bug" error. A cap lowered below the default is a tripwire for runaway casters
    // (tests set it), not a limit on the step: the step may always use the default cap.
    const double cap = double(std::max(s.maxIterationsPerRay, RenderSettings{}.maxIterationsPerRay));
    const double diagonal = length(grid.extent()), spacing = grid.smallestSpacing();
    const double samples = std::ceil(diagonal / (s.stepVoxels * spacing));
    if (samples <= cap) return;
    char text[240];
    std::snprintf(text, sizeof text,
                  "--step %g: too small for this volume: a ray across it takes up to %.3g samples, more than the "
                  "iteration cap of %.0f per ray; the smallest step it allows is %.3g voxels",
                  s.stepVoxels, samples, cap, diagonal / (cap * spacing));
    throw InputError(text);
}

void checkRenderInputs(const PreparedVolume& prepared, const RenderSettings& s) {
    const ClassifiedVolume& cv = prepared.classified;
    const std::size_t voxels = cv.grid.voxels();
    if (voxels == 0 || cv.sigma.size() != voxels || cv.colour.size() != voxels)
        throw InputError("prepared volume: classified data does not match its grid");
    checkRenderSettings(cv.grid, prepared.meta.segmentation.trilinear, s);
    if (s.shading && cv.normal.size() != voxels)
        throw InputError("prepared volume has no normals: shading needs them (prepare with normals or render "
                         "without shading)");
    const std::string caster(casterName(s.caster));
    auto need = [&](bool present, std::size_t size, const char* field) {
        if (!present || size != voxels)
            throw InputError("prepared volume has no " + std::string(field) + " field: the " + caster +
                             " caster needs it");
    };
    if (s.caster == Caster::PC) need(prepared.fields.hasPC(), prepared.fields.pc.size(), "PC");
    if (s.caster == Caster::ACD)
        for (const auto& f : prepared.fields.acd) need(prepared.fields.hasACD(), f.size(), "ACD");
    if (s.caster == Caster::EACD)
        for (const auto& f : prepared.fields.eacd) need(prepared.fields.hasEACD(), f.size(), "EACD");
}

void checkRenderSettings(const GridGeometry& grid, bool segmentedForTrilinear, const RenderSettings& s) {
    if (!(s.stepVoxels > 0) || !std::isfinite(s.stepVoxels))
        throw InputError("--step " + std::to_string(s.stepVoxels) + ": the step must be a positive number of voxels");
    requireLatticeFits(grid, s.stepVoxels);  // first: an absurd spacing is named as such, not as a tiny step
    requireSamplesWithinCap(grid, s);
    if (!(s.ert > 0 && s.ert <= 1))
        throw InputError("--ert " + std::to_string(s.ert) + ": early ray termination must be in (0, 1]");
    if (s.lightDirection && !(length(*s.lightDirection) > 0 && std::isfinite(length(*s.lightDirection))))
        throw InputError("--light: the light direction must be a finite non-zero vector");
    if (s.trilinear && s.caster != Caster::Primitive && !segmentedForTrilinear)
        throw InputError("trilinear sampling with the " + std::string(casterName(s.caster)) +
                         " caster needs a volume segmented for trilinear sampling (border voxels)");
}

}  // namespace vr
