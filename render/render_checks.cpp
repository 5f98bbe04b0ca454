#include "render/render_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/errors.h"
#include "core/number_text.h"
#include "render/ray_setup.h"
#include "shaders/device_contract.h"

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

void checkBlend(const RenderSettings& s) {
    const std::string caster(casterName(s.caster)), blend(blendName(s.blend));
    // The regions are made of one classification each, which bounds no scalar: a leap through them could pass a
    // larger maximum or an iso-crossing.
    if (s.blend != Blend::Composite && leapsThroughRegions(s.caster))
        throw InputError("--caster " + caster + " with --blend " + blend + ": the " + caster +
                         " caster leaps through regions of one classification, which do not bound the scalar a " +
                         blend + " blend follows (use --caster blocks or primitive)");
    if (s.blend == Blend::Composite && s.caster == Caster::Blocks)
        throw InputError("--caster blocks with --blend composite: the blocks caster leaps by scalar extrema, for "
                         "--blend mip, minip, average or iso (composite leaps with pc, acd or eacd)");
    if (s.blend == Blend::Iso && !std::isfinite(s.isoValue))
        throw InputError("--iso: the iso-value must be a finite number");
}

void checkLabelledBlend(bool labelled, const RenderSettings& s) {
    if (labelled && s.blend != Blend::Composite)
        throw InputError("--labels with --blend " + std::string(blendName(s.blend)) + ": a label map shows in the "
                         "composite blend only (mip, minip, average and iso follow the scalar alone)");
}

void checkRenderInputs(const PreparedVolume& prepared, const RenderSettings& s) {
    const GridGeometry& grid = prepared.grid();
    const std::size_t voxels = grid.voxels();
    if (voxels == 0 || heldVoxels(prepared.scalars) != voxels)
        throw InputError("prepared volume: the scalars do not match its grid");
    const TransferTable& table = prepared.classification.table;
    if (table.size() == 0 || table.colour.size() != table.size() || !(table.step > 0) || !std::isfinite(table.lo))
        throw InputError("prepared volume: the transfer table is empty or inconsistent");
    checkRenderSettings(grid, prepared.meta.segmentation, s);
    if (const auto& labels = prepared.labels) {
        const LabelClasses& c = labels->classes;
        if (labels->label.size() != voxels || c.size() == 0 || c.sigma.size() != c.size() ||
            c.colour.size() != c.size())
            throw InputError("prepared volume: the label map does not match its grid or its classes");
    }
    checkLabelledBlend(prepared.labels.has_value(), s);
    const std::string caster(casterName(s.caster));
    auto need = [&](bool present, std::size_t size, const char* field) {
        if (!present || size != voxels)
            throw InputError("prepared volume has no " + std::string(field) + " field: the " + caster +
                             " caster needs it");
    };
    if (s.caster == Caster::PC) need(prepared.fields.hasPC(), prepared.fields.pc.size(), "PC");
    // ACD and EACD may hold only some octants (those a render's views need): each held octant covers every voxel.
    if (s.caster == Caster::ACD)
        for (const auto& f : prepared.fields.acd) need(prepared.fields.hasACD(), f.empty() ? voxels : f.size(), "ACD");
    if (s.caster == Caster::EACD)
        for (const auto& f : prepared.fields.eacd)
            need(prepared.fields.hasEACD(), f.empty() ? voxels : f.size(), "EACD");
    if (s.caster == Caster::Hier) {  // over blocks: each held octant covers every block
        const BlockEACD& h = prepared.fields.hier;
        const int edge = 1 << h.blockShift;
        const bool covers = h.blockShift >= 0 && h.blockShift < 8 &&
                            h.blocks == Vec3i{(grid.dims.x + edge - 1) / edge, (grid.dims.y + edge - 1) / edge,
                                              (grid.dims.z + edge - 1) / edge};
        for (const auto& f : h.octant)
            need(!h.empty() && covers, f.empty() || f.size() == voxelCount(h.blocks) ? voxels : 0, "hier");
    }
}

static std::string planeText(const ClipPlane& p) {
    char text[128];
    std::snprintf(text, sizeof text, "--clip %g,%g,%g,%g", p.normal.x, p.normal.y, p.normal.z, p.offset);
    return text;
}

void checkClipPlanes(const std::vector<ClipPlane>& planes) {
    if (planes.size() > std::size_t(device::kMaxClipPlanes))
        throw InputError("--clip given " + std::to_string(planes.size()) + " times: at most " +
                         std::to_string(device::kMaxClipPlanes) + " planes");
    for (const ClipPlane& p : planes) {
        const double n = length(p.normal);
        if (!(n > 0) || !std::isfinite(n))
            throw InputError(planeText(p) + ": the normal must be a non-zero finite vector");
        if (!std::isfinite(p.offset)) throw InputError(planeText(p) + ": the offset must be a finite number");
    }
}

void checkCrop(const GridGeometry& grid, const CropBox& crop) {
    static constexpr const char* kAxes[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        const std::string range = std::to_string(crop.lo[a]) + ".." + std::to_string(crop.hi[a]);
        if (crop.lo[a] > crop.hi[a])
            throw InputError("--crop: voxels " + range + " on " + kAxes[a] + " are none (the first is after the last)");
        if (crop.lo[a] < 0 || crop.hi[a] >= grid.dims[a])
            throw InputError("--crop: voxels " + range + " on " + kAxes[a] + " reach outside the grid's 0.." +
                             std::to_string(grid.dims[a] - 1));
    }
}

void checkStepAndTermination(double stepVoxels, double ert) {
    if (!(stepVoxels > 0) || !std::isfinite(stepVoxels))
        throw InputError("--step " + numberText(stepVoxels) + ": the step must be a positive finite number of voxels");
    if (!(ert > 0 && ert <= 1))
        throw InputError("--ert " + numberText(ert) + ": must be in (0, 1], the opacity at which a ray ends");
}

void checkRenderSettings(const GridGeometry& grid, const SegmentationParams& segmentation, const RenderSettings& s) {
    checkClipPlanes(s.clipPlanes);
    if (s.crop) checkCrop(grid, *s.crop);
    checkStepAndTermination(s.stepVoxels, s.ert);
    requireLatticeFits(grid, s.stepVoxels);  // first: an absurd spacing is named as such, not as a tiny step
    requireSamplesWithinCap(grid, s);
    if (s.lightDirection && !(length(*s.lightDirection) > 0 && std::isfinite(length(*s.lightDirection))))
        throw InputError("--light: the light direction must be a finite non-zero vector");
    checkBlend(s);
    // The hier caster's blocks take their voxels' footprints whatever the file's regions were made for (docs/
    // ALGORITHMS.md section 10).
    if (s.trilinear && leapsThroughRegions(s.caster) && s.caster != Caster::Hier && !segmentation.trilinear)
        throw InputError("trilinear sampling with the " + std::string(casterName(s.caster)) +
                         " caster needs a volume segmented for trilinear sampling (volprep without --nearest; or "
                         "render with --nearest)");
    // Regions that ignored the normals would let a leap carry one shade across a change of normal.
    if (s.shading && s.blend == Blend::Composite && leapsThroughRegions(s.caster) && !segmentation.useNormals)
        throw InputError("shading with the " + std::string(casterName(s.caster)) +
                         " caster needs regions made with normals (prepared with --no-normals: render without "
                         "shading, or with the primitive caster)");
}

}  // namespace vr
