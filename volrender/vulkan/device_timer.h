// The device time of a command buffer's work: a timestamp at its start and one at its end.
#pragma once
#include <cstdint>

#include "volrender/vulkan/vulkan_context.h"

namespace vr {

class DeviceTimer {
public:
    explicit DeviceTimer(const VulkanContext& ctx);
    void start(const vk::raii::CommandBuffer& cmd) const;  // resets the queries, then the first timestamp
    void stop(const vk::raii::CommandBuffer& cmd) const;
    // Between the two, once the commands are done (waits for them); 0 where the queue has no timestamps.
    double milliseconds() const;

private:
    vk::raii::QueryPool queries_{nullptr};
    double periodNs_ = 0;  // 0: the queue has no timestamps
    uint64_t mask_ = 0;
};

}  // namespace vr
