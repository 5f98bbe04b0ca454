// The Vulkan side of the render tests (library vrvulkansupport): one validated context per test process, renderers
// on it, and the check every Vulkan test ends with.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "support/render_cases.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr::test {

// The test process's Vulkan context (the default device), with VK_LAYER_KHRONOS_validation on.
VulkanContext& vulkanContext();

// A renderer on vulkanContext() drawing tiles of tileSize x tileSize pixels (one submit each), one per tile size
// and process: tests choose tiles smaller than their images, so that full and partial tiles both run. It re-casts
// a stereo pair's pixels as whole rays on every device, so that they are the full render's.
VulkanRenderer& vulkanRenderer(int tileSize);
// vulkanRenderer(tileSize) as a RenderFn.
RenderFn vulkanRender(int tileSize);

// Validation is on, and the layer has reported no error since vulkanContext() was made.
void expectNoValidationErrors();
// report(family, n), then expectNoValidationErrors().
void reportValidated(const char* family, const CaseCount& n);

// Bytes per resource name ("scalars", "table", "pc", "acd", "eacd"), summed over bricks.
std::map<std::string, std::size_t> bytesByName(const std::vector<UploadedResource>& uploads);

}  // namespace vr::test
