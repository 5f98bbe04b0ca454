// The report volprep prints when it is done: what the stages produced and what each cost.
#pragma once
#include <cstdio>
#include <filesystem>

#include "preprocess/pipeline/prepare.h"

namespace vr {

void printSummary(std::FILE* out, const std::filesystem::path& output, const PrepareResult& result);

}  // namespace vr
