#include "volrender/cmd/auto_caster.h"

#include <algorithm>

#include "volrender/cmd/calibration_in_use.h"

namespace vr {
namespace {

// What the views ask of a volume of `grid` whose scalars are of `type`: each camera's octants and direction classes.
CasterDemand demandOf(const std::vector<Camera>& cameras, const RenderSettings& s, const GridGeometry& grid,
                      ScalarType type) {
    CasterDemand d{0, {}, (long long)cameras.front().width * cameras.front().height, s.stepVoxels};
    for (const Camera& camera : cameras) d.addView(camera);
    d.scalarBytes = scalarBytesOnDevice(grid, type);
    return d;
}

}  // namespace

CasterChoice autoCasterForFile(const PreparedHeader& header, const std::vector<Camera>& cameras,
                               const RenderSettings& s, const CasterCalibration& calibration) {
    if (s.trilinear && !header.meta.segmentation.trilinear)
        return {Caster::Primitive, "the regions were made for nearest sampling only (volprep --nearest): "
                                   "trilinear sampling cannot leap through them (render with --nearest to leap)"};
    if (s.shading && s.blend == Blend::Composite && !header.meta.segmentation.useNormals)
        return {Caster::Primitive, "the regions were made without normals (volprep --no-normals): a shaded render "
                                   "cannot leap through them (render with --no-shading to leap)"};
    return chooseCaster(header.meta.rayProbe, header.fieldBytes,
                        demandOf(cameras, s, header.grid, header.scalarType), calibration);
}

std::optional<std::string> deviceToCalibrate(const std::string& calibrationFlag, OpeningDevice& device) {
    if (!calibrationReadsFile(calibrationFlag)) return std::nullopt;
    return device.context().info().name;
}

CasterChoice autoCasterBeforeFields(const std::string& calibrationFlag, const RenderSettings& s,
                                    StagedPreparation& staged, PrepareOptions options,
                                    const std::vector<Camera>& cameras, OpeningDevice& device) {
    const CalibrationInUse calibration = calibrationInUse(calibrationFlag, deviceToCalibrate(calibrationFlag, device));
    RenderSettings probe = s;
    probe.caster = Caster::Primitive;
    const PreparedVolume& classified = staged.prepare(options, PrepStage::Classify);
    CasterDemand d = demandOf(cameras, s, classified.grid(), classified.scalars.sourceType);
    ProbedIterations it{probeIterations(classified, cameras, probe), {}};
    const std::size_t voxels = classified.grid().voxels();
    // A label map, not the scalars, would decide what a block holds: hier does not take one.
    if (!classified.labels && hierMayPay(it.primitive, d, voxels, calibration.constants)) {
        options.fields = kFieldHier;
        probe.caster = Caster::Hier;
        it.hier = probeIterations(staged.prepare(options), cameras, probe);
    }
    d.deviceWaitMs = device.waitMs();
    return chooseBeforeBuilding(it, d, voxels, calibration.constants);
}

CasterChoice autoBlendCaster(const PreparedVolume& classified, const RenderSettings& s,
                             const std::vector<Camera>& cameras, const CasterCalibration& calibration) {
    const CasterDemand d = demandOf(cameras, s, classified.grid(), classified.scalars.sourceType);
    const std::size_t probedViews = std::min<std::size_t>(cameras.size(), 4);
    std::vector<Camera> probed;
    for (std::size_t i = 0; i < probedViews; ++i) probed.push_back(cameras[i * cameras.size() / probedViews]);
    RenderSettings probe = s;
    probe.caster = Caster::Primitive;
    const double primitive = probeIterations(classified, probed, probe);
    probe.caster = Caster::Blocks;
    const double blocks = probeIterations(classified, probed, probe);
    return chooseBlendCaster(primitive, blocks, d, classified.grid().voxels(), calibration);
}

}  // namespace vr
