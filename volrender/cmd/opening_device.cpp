#include "volrender/cmd/opening_device.h"

#include "render/caster_choice.h"
#include "volrender/cmd/process_timeline.h"

namespace vr {

OpeningDevice::OpeningDevice(int deviceIndex)
    : start_(std::chrono::steady_clock::now()), opening_(std::async(std::launch::async, [deviceIndex] {
          auto d = std::make_shared<Opened>();
          d->context = std::make_unique<VulkanContext>(VulkanOptions{deviceIndex, false});
          markMilestone("deviceOpened");
          d->renderer = std::make_unique<VulkanRenderer>(*d->context);
          markMilestone("rendererMade");
          return d;
      })) {}

void OpeningDevice::preparePipelines(std::vector<Caster> casters, RenderSettings settings, Projection projection,
                                     ScalarType type, bool stereoReuse) {
    preparing_ = std::async(std::launch::async, [this, opening = opening_, casters, settings, projection, type,
                                                  stereoReuse]() mutable {
        try {
            // The device first: a choice made while it opens skips every other caster's pipeline.
            VulkanRenderer& renderer = *opening.get()->renderer;
            for (Caster caster : casters) {
                const int chosen = chosen_;
                if (chosen >= 0 && chosen != int(caster)) continue;
                settings.caster = caster;
                if (stereoReuse) renderer.prepareStereoPipelines(settings, type);
                else renderer.preparePipeline(settings, projection, type);
                markMilestone("pipelineMade");
            }
        } catch (const std::exception&) {
        }
    });
}

double OpeningDevice::waitMs() const {
    const std::chrono::duration<double, std::milli> since = std::chrono::steady_clock::now() - start_;
    return deviceWaitMs(since.count(), opening_.wait_for(std::chrono::seconds(0)) == std::future_status::ready);
}

}  // namespace vr
