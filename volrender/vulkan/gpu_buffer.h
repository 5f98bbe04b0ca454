// Device memory the casters use: host-visible buffers (uniforms, staging, readback) and 3D images (volumes).
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/vec3.h"
#include "volrender/vulkan/vulkan_context.h"

namespace vr {

// A buffer in host-visible, coherent memory, mapped for its lifetime.
class HostBuffer {
public:
    HostBuffer(const VulkanContext& ctx, vk::DeviceSize bytes, vk::BufferUsageFlags usage);
    const vk::raii::Buffer& buffer() const { return buffer_; }
    vk::DeviceSize size() const { return size_; }
    void* data() const { return mapped_; }

private:
    vk::raii::Buffer buffer_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    vk::DeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

// A 3D image in device-local memory, filled once from host texels and then only read (texelFetch).
class VolumeImage {
public:
    VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                const void* texels, std::size_t texelBytes);
    const vk::raii::ImageView& view() const { return view_; }
    std::size_t bytes() const { return bytes_; }  // texel bytes uploaded

private:
    vk::raii::Image image_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    vk::raii::ImageView view_{nullptr};
    std::size_t bytes_ = 0;
};

// Records commands into a fresh one-time command buffer, submits it and waits for it.
template <typename Record>
void submitAndWait(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Record&& record) {
    vk::raii::CommandBuffers cmds(ctx.device(), vk::CommandBufferAllocateInfo(*pool, vk::CommandBufferLevel::ePrimary, 1));
    vk::raii::CommandBuffer& cmd = cmds[0];
    cmd.begin(vk::CommandBufferBeginInfo(vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
    record(cmd);
    cmd.end();
    vk::raii::Fence fence(ctx.device(), vk::FenceCreateInfo());
    vk::CommandBuffer handle = *cmd;
    ctx.queue().submit(vk::SubmitInfo({}, {}, handle), *fence);
    (void)ctx.device().waitForFences(*fence, VK_TRUE, UINT64_MAX);
}

}  // namespace vr
