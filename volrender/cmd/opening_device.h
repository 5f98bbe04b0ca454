// The Vulkan device of a volrender run and its renderer, opened on a thread of their own while the volume loads: a
// CPU device's start (its driver's libraries, the instance, the device) takes as long as loading and classifying a
// small CT, a GPU driver's longer.
#pragma once
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <vector>

#include "render/render_settings.h"
#include "volrender/vulkan/vulkan_context.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {

class OpeningDevice {
public:
    explicit OpeningDevice(int deviceIndex);
    // Wait for it to open; rethrow why it could not.
    VulkanContext& context() { return *opening_.get()->context; }
    VulkanRenderer& renderer() { return *opening_.get()->renderer; }

    // Makes the pipelines of renders with `settings` by each of `casters` in turn (VulkanRenderer::preparePipeline),
    // on a thread of their own once the device is open, while the volume is still being prepared: a CPU device
    // takes about as long to make one as to render a small CT. Once chose() names the caster, the others are
    // skipped. A pipeline that cannot be made is left to the render, which says why. `stereoReuse`: the renders are
    // stereo pairs with reuse (VulkanRenderer::prepareStereoPipelines).
    void preparePipelines(std::vector<Caster> casters, RenderSettings settings, Projection projection,
                          ScalarType type, bool stereoReuse = false);
    void chose(Caster caster) { chosen_ = int(caster); }

    // What the first view waits for from now (deviceWaitMs): the rest of the device's start, then a pipeline.
    double waitMs() const;

private:
    struct Opened {
        std::unique_ptr<VulkanContext> context;
        std::unique_ptr<VulkanRenderer> renderer;
    };
    std::chrono::steady_clock::time_point start_;
    std::shared_future<std::shared_ptr<Opened>> opening_;
    std::atomic<int> chosen_{-1};  // the caster, once known
    std::future<void> preparing_;  // joined before the device closes
};

}  // namespace vr
