// --caster auto: which caster to render a view with, chosen among the fields a prepared volume holds. At
// preparation the ray probe counts each caster's iterations per direction class on small CPU renders (kept in the
// prepared file); at render time the choice weighs them, and the fields' bytes, for the views asked.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "io/caster_calibration_file.h"
#include "render/direction_class.h"
#include "render/render_settings.h"

namespace vr {

// Per direction class (render/direction_class.h: the 8 octants, 12 plane quadrants and 6 axes) and per caster the
// fields allow, the mean loop iterations per pixel of the CPU reference renderer (the casters' own loop: lattice,
// leaps, early ray termination; nearest sampling, unshaded) over small orthographic views along directions of the
// class, at the renderer's default step and at half of it to split leaps from single samples. None for a volume
// whose rays are too long to probe (spacings far apart: more than 2^17 samples across).
std::optional<RayProbe> probeRays(const PreparedVolume& prepared);

// The mean loop iterations per pixel over `cameras` of the caster of `settings`, from the CPU reference casting each
// view at about 16 x 16 pixels over its whole frustum with the sampling of `settings` (unshaded: shading does not
// change where a ray ends). The primitive caster needs only the scalars and their classification, hier its field:
// the probe of a volume before any field over voxel regions is built.
double probeIterations(const PreparedVolume& prepared, const std::vector<Camera>& cameras,
                       const RenderSettings& settings);

// The views to render, which share one upload of the field.
struct CasterDemand {
    unsigned octants = 0;          // ray octants the views have (viewOctants): the ACD / EACD octants uploaded
    std::vector<unsigned> views;   // per view, the ray probe's direction classes its rays fall in
    long long pixels = 512 * 512;  // per view
    double stepVoxels = 0.5;
    // The volume's scalars on the device (voxels x their type's bytes), which every iteration samples: beyond the
    // caches an iteration costs more (iterationScale). 0 when unknown: priced as a volume the caches hold.
    double scalarBytes = 0;
    // Milliseconds the first view waits for the device from the choice on (deviceWaitMs), during which a field
    // builds on the side for free: a volume prepared in the same process as the render. 0: no such wait.
    double deviceWaitMs = 0;

    void addView(const Camera& camera) {
        octants |= viewOctants(camera);
        views.push_back(viewDirectionClasses(camera));
    }
};

struct CasterChoice {
    Caster caster = Caster::Primitive;
    std::string reason;  // one line: each candidate's estimated iterations per pixel and relative cost
};

// The model's constants measured on lavapipe with 2 cores (see caster_choice.cpp): what --caster auto uses on a
// device without a calibration file of its own.
const CasterCalibration& builtInCalibration();

// A volume's scalars' bytes on the device, in their own type as the casters sample them: CasterDemand::scalarBytes.
double scalarBytesOnDevice(const GridGeometry& grid, ScalarType type);

// The factor on every caster's time per iteration for a volume of `scalarBytes` on the device: 1 up to the growth's
// cachedBytes, then 1 + perDoubling x log2(scalarBytes / cachedBytes); 1 where the growth or the bytes are 0.
double iterationScale(const IterationGrowth& growth, double scalarBytes);

// Estimates each available caster's time as pixels x (a cost per ray + iterations per pixel x its time per
// iteration, scaled for the volume's bytes by iterationScale) per view, the iterations from the probe for the view's
// direction classes (rescaled to the step), plus the upload of its field (`fieldBytes`, per octant uploaded) shared
// by the views, and returns the cheapest; when a leaner caster is within the calibration's tie of it, the one with
// less to upload. Without a probe (an old or foreign file, or rays too long to probe) the primitive caster, which
// needs no field, and a reason that says so.
CasterChoice chooseCaster(const std::optional<RayProbe>& probe, const FieldBytes& fieldBytes,
                          const CasterDemand& demand,
                          const CasterCalibration& calibration = builtInCalibration());

// What --caster auto knows of a volume prepared in the same process before a field over voxel regions is built: the
// mean iterations per pixel of the views (probeIterations) with the primitive caster, which needs no field, and with
// the hier caster where its field was built (hierMayPay).
struct ProbedIterations {
    double primitive = 0;
    std::optional<double> hier;
};

// What the first view of a one-command render waits for from now, beside which a field builds: what is left of the
// device's start (its driver's libraries, the instance and the device), `sinceOpeningMs` after it began, unless it
// is `open`, then the caster's pipeline, made once the caster is chosen. Measured on lavapipe on this project's
// 2-core machine (caster_choice.cpp); a GPU's driver starts more slowly, so the choice then errs toward building.
double deviceWaitMs(double sinceOpeningMs, bool open);

// Whether the hier field, built at a cost per voxel measured on this project's 2-core machine (caster_choice.cpp),
// can pay for itself: the views cast without a field (primitiveIterations per pixel) cost more than its build.
bool hierMayPay(double primitiveIterations, const CasterDemand& demand, std::size_t voxels,
                const CasterCalibration& calibration = builtInCalibration());

// --caster auto for a volume prepared in the same process, before any field over voxel regions is built: the
// cheapest of the primitive caster (its views), hier (its views: its field is built already) and EACD (segmentation
// and its field, priced per voxel as measured on this project's 2-core machine, plus its views at hier's iterations
// times the ratio of EACD's to hier's measured on the shared CTs; without a hier probe its views are not priced,
// so that EACD is taken only where no render of it could lose). Hier iterations are priced as EACD's (the same
// work: a field fetch, a decode, a box exit). More cores build faster, so the rule then errs toward building. With
// its views priced, EACD's build costs only the part of it that outlasts the demand's deviceWaitMs. (The hier field
// is built only where it may pay without that wait, so that a primitive render builds nothing.)
CasterChoice chooseBeforeBuilding(const ProbedIterations& iterations, const CasterDemand& demand, std::size_t voxels,
                                  const CasterCalibration& calibration = builtInCalibration());

// --caster auto for the blends other than composite (MIP, MinIP, average, iso), which leap by the blocks' scalar
// extrema or not at all: the primitive caster or blocks, whichever casts the views in less time. Each takes its
// probed iterations per pixel (probeIterations, with the blend); a blocks iteration costs the calibration's
// blocksIterationRatio times a primitive one (the built-in ratio where the calibration has none), plus the block
// extrema's build per voxel. A tie goes to the primitive caster, which builds and uploads nothing more.
CasterChoice chooseBlendCaster(double primitiveIterations, double blocksIterations, const CasterDemand& demand,
                               std::size_t voxels, const CasterCalibration& calibration = builtInCalibration());

}  // namespace vr
