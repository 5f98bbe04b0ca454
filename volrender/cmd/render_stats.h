// The --stats JSON of one rendered view: timings, work per ray, uploaded bytes.
#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "render/render_result.h"
#include "volrender/vulkan/gpu_volume.h"

namespace vr {

// Iterations per ray (mean, p95, max) over all pixels, samples represented (total, mean per ray), device and
// wall milliseconds, and the bytes of every resource on the device for it, summed over bricks (empty for the CPU
// renderer).
nlohmann::json viewStatistics(const RenderResult& result, const std::vector<UploadedResource>& uploads);

// What one upload put on the device: its milliseconds, the bytes per resource (summed over bricks) and each
// brick's box and bytes per resource.
nlohmann::json uploadStatistics(const GpuVolume& volume, double milliseconds);

}  // namespace vr
