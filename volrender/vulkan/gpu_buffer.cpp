#include "volrender/vulkan/gpu_buffer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace vr {

HostBuffer::HostBuffer(const VulkanContext& ctx, vk::DeviceSize bytes, vk::BufferUsageFlags usage) : size_(bytes) {
    buffer_ = vk::raii::Buffer(ctx.device(), vk::BufferCreateInfo({}, bytes, usage));
    auto req = buffer_.getMemoryRequirements();
    using M = vk::MemoryPropertyFlagBits;
    // Host-cached memory reads back faster; coherent memory needs no flushes.
    uint32_t type = ctx.memoryType(req.memoryTypeBits, M::eHostVisible | M::eHostCoherent, M::eHostCached);
    memory_ = vk::raii::DeviceMemory(ctx.device(), vk::MemoryAllocateInfo(req.size, type));
    buffer_.bindMemory(*memory_, 0);
    mapped_ = memory_.mapMemory(0, bytes);
}

VolumeImage::VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                         const void* texels, std::size_t texelBytes)
    : bytes_(texelBytes) {
    using U = vk::ImageUsageFlagBits;
    vk::Extent3D extent(uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z));
    auto limits = ctx.physicalDevice().getProperties().limits;
    if (std::max({extent.width, extent.height, extent.depth}) > limits.maxImageDimension3D)
        throw std::runtime_error("a volume of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                 std::to_string(dims.z) + " texels exceeds the device's 3D image limit of " +
                                 std::to_string(limits.maxImageDimension3D));
    image_ = vk::raii::Image(ctx.device(), vk::ImageCreateInfo({}, vk::ImageType::e3D, format, extent, 1, 1,
                                                               vk::SampleCountFlagBits::e1, vk::ImageTiling::eOptimal,
                                                               U::eSampled | U::eTransferDst));
    auto req = image_.getMemoryRequirements();
    memory_ = vk::raii::DeviceMemory(
        ctx.device(),
        vk::MemoryAllocateInfo(req.size, ctx.memoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal)));
    image_.bindMemory(*memory_, 0);

    HostBuffer staging(ctx, texelBytes, vk::BufferUsageFlagBits::eTransferSrc);
    std::memcpy(staging.data(), texels, texelBytes);
    vk::ImageSubresourceRange range(vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1);
    submitAndWait(ctx, pool, [&](const vk::raii::CommandBuffer& cmd) {
        using A = vk::AccessFlagBits;
        using S = vk::PipelineStageFlagBits;
        vk::ImageMemoryBarrier toDst({}, A::eTransferWrite, vk::ImageLayout::eUndefined,
                                     vk::ImageLayout::eTransferDstOptimal, VK_QUEUE_FAMILY_IGNORED,
                                     VK_QUEUE_FAMILY_IGNORED, *image_, range);
        cmd.pipelineBarrier(S::eTopOfPipe, S::eTransfer, {}, {}, {}, toDst);
        vk::BufferImageCopy copy(0, 0, 0, vk::ImageSubresourceLayers(vk::ImageAspectFlagBits::eColor, 0, 0, 1),
                                 {0, 0, 0}, extent);
        cmd.copyBufferToImage(*staging.buffer(), *image_, vk::ImageLayout::eTransferDstOptimal, copy);
        vk::ImageMemoryBarrier toRead(A::eTransferWrite, A::eShaderRead, vk::ImageLayout::eTransferDstOptimal,
                                      vk::ImageLayout::eShaderReadOnlyOptimal, VK_QUEUE_FAMILY_IGNORED,
                                      VK_QUEUE_FAMILY_IGNORED, *image_, range);
        cmd.pipelineBarrier(S::eTransfer, S::eComputeShader, {}, {}, {}, toRead);
    });
    view_ = vk::raii::ImageView(ctx.device(), vk::ImageViewCreateInfo({}, *image_, vk::ImageViewType::e3D, format, {},
                                                                      range));
}

}  // namespace vr
