// What the stages produced, for the prepared file's metadata.statistics (informative: docs/PREPARED_FORMAT.md).
#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "core/prepared_volume.h"
#include "preprocess/pipeline/stage_time.h"

namespace vr {

// Voxels, regions, mean region size, mean leap per field and octant (PC radius, ACD edge, EACD extents), bytes per
// chunk group and the stage times given.
nlohmann::json preparedStatistics(const PreparedVolume& prepared, const std::vector<StageTime>& stages);

}  // namespace vr
