// The report volprep prints when it is done: what the stages produced and what each cost.
#pragma once
#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/prepared_volume.h"
#include "preprocess/pipeline/stage_time.h"

namespace vr {

// `prepared` as written to `output` by the stages timed in `stages` (in the order they ran).
void printSummary(std::FILE* out, const std::filesystem::path& output, const PreparedVolume& prepared,
                  const std::vector<StageTime>& stages);

}  // namespace vr
