#include "volrender/vulkan/device_timer.h"

namespace vr {

DeviceTimer::DeviceTimer(const VulkanContext& ctx) {
    queries_ = vk::raii::QueryPool(ctx.device(), vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, 2));
    const uint32_t validBits = ctx.physicalDevice().getQueueFamilyProperties()[ctx.queueFamily()].timestampValidBits;
    if (validBits > 0) {
        periodNs_ = ctx.physicalDevice().getProperties().limits.timestampPeriod;
        mask_ = validBits >= 64 ? ~uint64_t(0) : (uint64_t(1) << validBits) - 1;
    }
}

void DeviceTimer::start(const vk::raii::CommandBuffer& cmd) const {
    cmd.resetQueryPool(*queries_, 0, 2);
    cmd.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries_, 0);
}

void DeviceTimer::stop(const vk::raii::CommandBuffer& cmd) const {
    cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries_, 1);
}

double DeviceTimer::milliseconds() const {
    if (periodNs_ == 0) return 0;
    auto [status, stamps] = queries_.getResults<uint64_t>(
        0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t), vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
    (void)status;
    return double((stamps[1] - stamps[0]) & mask_) * periodNs_ * 1e-6;
}

}  // namespace vr
