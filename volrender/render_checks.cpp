#include "render_checks.h"

#include <cmath>
#include <string>

#include "core/errors.h"
#include "ray_setup.h"

namespace vr {

void checkRenderInputs(const PreparedVolume& prepared, const RenderSettings& s) {
    const ClassifiedVolume& cv = prepared.classified;
    const std::size_t voxels = cv.grid.voxels();
    if (voxels == 0 || cv.sigma.size() != voxels || cv.colour.size() != voxels)
        throw InputError("prepared volume: classified data does not match its grid");
    if (!(s.stepVoxels > 0) || !std::isfinite(s.stepVoxels))
        throw InputError("--step " + std::to_string(s.stepVoxels) + ": the step must be a positive number of voxels");
    requireLatticeFits(cv.grid, s.stepVoxels);
    if (!(s.ert > 0 && s.ert <= 1))
        throw InputError("--ert " + std::to_string(s.ert) + ": early ray termination must be in (0, 1]");
    if (s.shading && cv.normal.size() != voxels)
        throw InputError("prepared volume has no normals: shading needs them (prepare with normals or render "
                         "without shading)");
    if (s.lightDirection && !(length(*s.lightDirection) > 0 && std::isfinite(length(*s.lightDirection))))
        throw InputError("--light: the light direction must be a finite non-zero vector");
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
    if (s.trilinear && s.caster != Caster::Primitive && !prepared.meta.segmentation.trilinear)
        throw InputError("trilinear sampling with the " + caster +
                         " caster needs a volume segmented for trilinear sampling (border voxels)");
}

}  // namespace vr
