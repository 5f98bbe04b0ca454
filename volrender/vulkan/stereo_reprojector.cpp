#include "volrender/vulkan/stereo_reprojector.h"

#include <cstring>

#include "shaders/embedded_shaders.h"

namespace vr {

StereoReprojector::StereoReprojector(const VulkanContext& ctx)
    : ctx_(ctx), timer_(ctx), unusedBands_(ctx, 16, kBandSegmentUsage) {
    using T = vk::DescriptorType;
    const auto compute = vk::ShaderStageFlagBits::eCompute;
    const std::array<vk::DescriptorSetLayoutBinding, 5> bindings{{
        {device::kBindingStereoParams, T::eUniformBuffer, 1, compute},
        {device::kBindingLeftPixels, T::eStorageBuffer, 1, compute},
        {device::kBindingRightPixels, T::eStorageBuffer, 1, compute},
        {device::kBindingRecastList, T::eStorageBuffer, 1, compute},
        {device::kBindingLeftBands, T::eStorageTexelBuffer, 1, compute}}};
    setLayout_ = vk::raii::DescriptorSetLayout(ctx.device(), vk::DescriptorSetLayoutCreateInfo({}, bindings));
    const vk::DescriptorSetLayout setLayout = *setLayout_;
    layout_ = vk::raii::PipelineLayout(ctx.device(), vk::PipelineLayoutCreateInfo({}, setLayout));
    shader_ = vk::raii::ShaderModule(ctx.device(), vk::ShaderModuleCreateInfo({}, stereo_reproject_spv));
}

int StereoReprojector::pipelineCount() {
    std::lock_guard lock(pipelinesMutex_);
    return (*intervals_ ? 1 : 0) + (*bands_ ? 1 : 0);
}

const vk::raii::Pipeline& StereoReprojector::pipeline(bool bands) {
    std::lock_guard lock(pipelinesMutex_);
    vk::raii::Pipeline& made = bands ? bands_ : intervals_;
    if (*made) return made;
    const VkBool32 value = bands;
    const vk::SpecializationMapEntry entry(device::kSpecIdBands, 0, sizeof value);
    const vk::SpecializationInfo specialization(1, &entry, sizeof value, &value);
    vk::PipelineShaderStageCreateInfo stage({}, vk::ShaderStageFlagBits::eCompute, *shader_, "main", &specialization);
    made = vk::raii::Pipeline(ctx_.device(), nullptr, vk::ComputePipelineCreateInfo({}, stage, *layout_));
    return made;
}

double StereoReprojector::reproject(const vk::raii::CommandPool& pool, const device::StereoParams& params,
                                    const HostBuffer& left, const DeviceBuffer* bands, const HostBuffer& right,
                                    const HostBuffer& recast) {
    HostBuffer uniform(ctx_, sizeof params, vk::BufferUsageFlagBits::eUniformBuffer);
    std::memcpy(uniform.data(), &params, sizeof params);
    const std::array<vk::DescriptorPoolSize, 3> sizes{
        vk::DescriptorPoolSize(vk::DescriptorType::eUniformBuffer, 1),
        vk::DescriptorPoolSize(vk::DescriptorType::eStorageBuffer, 3),
        vk::DescriptorPoolSize(vk::DescriptorType::eStorageTexelBuffer, 1)};
    vk::raii::DescriptorPool descriptorPool(
        ctx_.device(), vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, sizes));
    const vk::DescriptorSetLayout setLayout = *setLayout_;
    vk::raii::DescriptorSets sets(ctx_.device(), vk::DescriptorSetAllocateInfo(*descriptorPool, setLayout));
    const vk::DescriptorBufferInfo buffers[4] = {{*uniform.buffer(), 0, VK_WHOLE_SIZE},
                                                 {*left.buffer(), 0, VK_WHOLE_SIZE},
                                                 {*right.buffer(), 0, VK_WHOLE_SIZE},
                                                 {*recast.buffer(), 0, VK_WHOLE_SIZE}};
    const vk::raii::BufferView segments(
        ctx_.device(),
        vk::BufferViewCreateInfo({}, *(bands ? *bands : unusedBands_).buffer(), kBandSegmentFormat, 0, VK_WHOLE_SIZE));
    const vk::BufferView segmentView = *segments;
    using T = vk::DescriptorType;
    const vk::DescriptorSet set = *sets[0];
    const std::array<vk::WriteDescriptorSet, 5> writes{{
        {set, device::kBindingStereoParams, 0, 1, T::eUniformBuffer, nullptr, &buffers[0]},
        {set, device::kBindingLeftPixels, 0, 1, T::eStorageBuffer, nullptr, &buffers[1]},
        {set, device::kBindingRightPixels, 0, 1, T::eStorageBuffer, nullptr, &buffers[2]},
        {set, device::kBindingRecastList, 0, 1, T::eStorageBuffer, nullptr, &buffers[3]},
        {set, device::kBindingLeftBands, 0, 1, T::eStorageTexelBuffer, nullptr, nullptr, &segmentView}}};
    ctx_.device().updateDescriptorSets(writes, {});
    const vk::raii::Pipeline& pipe = pipeline(bands != nullptr);
    submitAndWait(ctx_, pool, [&](const vk::raii::CommandBuffer& cmd) {
        using S = vk::PipelineStageFlagBits;
        timer_.start(cmd);
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipe);
        cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout_, 0, set, {});
        cmd.dispatch(uint32_t((params.imageSize.x + device::kReprojectGroup - 1) / device::kReprojectGroup),
                     uint32_t(params.imageSize.y), 1);
        timer_.stop(cmd);
        vk::MemoryBarrier toHost(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
        cmd.pipelineBarrier(S::eComputeShader, S::eHost, {}, toHost, {}, {});
    });
    return timer_.milliseconds();
}

}  // namespace vr
