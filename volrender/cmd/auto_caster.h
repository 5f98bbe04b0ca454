// volrender --caster auto: the caster for the views' eye cameras, weighed by the cost model of render/caster_choice.h
// with a device's calibration, from a prepared file's header, from a volume classified in this process before any
// field over its regions is built, or for a blend other than composite.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "io/prepared_file.h"
#include "preprocess/pipeline/staged_prepare.h"
#include "render/caster_choice.h"
#include "volrender/cmd/opening_device.h"

namespace vr {

// From the ray probe and the field sizes in a prepared file's header (the chunks are read once the caster is known).
CasterChoice autoCasterForFile(const PreparedHeader& header, const std::vector<Camera>& cameras,
                               const RenderSettings& s, const CasterCalibration& calibration);

// The name of the device that auto chooses for, where the calibration it reads (--calibration `calibrationFlag`)
// must have been measured on it; else none, and no wait for the device to open: the choice's fields then build
// while it does.
std::optional<std::string> deviceToCalibrate(const std::string& calibrationFlag, OpeningDevice& device);

// For a volume prepared here, once it is classified and before any field over voxel regions is built: the
// primitive caster, hier (its field built here to probe it, where it can pay) or EACD, whichever the views and the
// builds cost least, priced with the constants of the device the render will run on (a build beside the device's
// start costs only what outlasts it).
CasterChoice autoCasterBeforeFields(const std::string& calibrationFlag, const RenderSettings& s,
                                    StagedPreparation& staged, PrepareOptions options,
                                    const std::vector<Camera>& cameras, OpeningDevice& device);

// For a blend other than composite: the primitive caster or blocks (chooseBlendCaster), each probed on the
// classified volume over at most 4 of the views, evenly spread (the blocks' probe builds their extrema once per
// view).
CasterChoice autoBlendCaster(const PreparedVolume& classified, const RenderSettings& s,
                             const std::vector<Camera>& cameras, const CasterCalibration& calibration);

}  // namespace vr
