#include "volrender/vulkan/gpu_buffer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/huge_pages.h"

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

DeviceBuffer::DeviceBuffer(const VulkanContext& ctx, vk::DeviceSize bytes, vk::BufferUsageFlags usage) {
    buffer_ = vk::raii::Buffer(ctx.device(), vk::BufferCreateInfo({}, bytes, usage));
    auto req = buffer_.getMemoryRequirements();
    memory_ = vk::raii::DeviceMemory(
        ctx.device(),
        vk::MemoryAllocateInfo(req.size, ctx.memoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal)));
    buffer_.bindMemory(*memory_, 0);
}

namespace {

constexpr vk::ImageUsageFlags kVolumeUsage = vk::ImageUsageFlagBits::eStorage | vk::ImageUsageFlagBits::eTransferDst;

vk::ImageCreateInfo volumeImageInfo(const Vec3i& dims, vk::Format format) {
    return vk::ImageCreateInfo({}, vk::ImageType::e3D, format,
                               vk::Extent3D(uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z)), 1, 1,
                               vk::SampleCountFlagBits::e1, vk::ImageTiling::eOptimal, kVolumeUsage);
}

}  // namespace

std::size_t formatBytes(vk::Format format) {
    switch (format) {
        case vk::Format::eR8Uint: return 1;
        case vk::Format::eR16Uint: return 2;
        case vk::Format::eR8G8B8A8Uint: return 4;
        case vk::Format::eR16G16B16A16Snorm: return 8;
        case vk::Format::eR32G32B32A32Sfloat: return 16;
        default: throw std::logic_error("formatBytes: a volume image format without its size here");
    }
}

bool imageFits(const VulkanContext& ctx, const Vec3i& extent, vk::Format format, const ImageLimits& limits) {
    const vk::raii::PhysicalDevice& gpu = ctx.physicalDevice();
    uint32_t maxDimension = gpu.getProperties().limits.maxImageDimension3D;
    if (limits.maxDimension > 0) maxDimension = std::min(maxDimension, limits.maxDimension);
    vk::ImageFormatProperties format3d;
    try {
        format3d = gpu.getImageFormatProperties(format, vk::ImageType::e3D, vk::ImageTiling::eOptimal,
                                                kVolumeUsage);
    } catch (const vk::FormatNotSupportedError&) {
        return false;
    }
    for (int a = 0; a < 3; ++a) {
        const uint32_t formatMax = a == 0 ? format3d.maxExtent.width : a == 1 ? format3d.maxExtent.height
                                                                              : format3d.maxExtent.depth;
        if (extent[a] < 1 || uint32_t(extent[a]) > std::min(maxDimension, formatMax)) return false;
    }
    // The memory the driver asks for, with its padding, against one allocation's limits.
    const vk::raii::Image probe(ctx.device(), volumeImageInfo(extent, format));
    const vk::MemoryRequirements req = probe.getMemoryRequirements();
    const auto props = gpu.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceMaintenance3Properties>();
    vk::DeviceSize maxBytes =
        std::min(props.get<vk::PhysicalDeviceMaintenance3Properties>().maxMemoryAllocationSize, format3d.maxResourceSize);
    const auto memory = gpu.getMemoryProperties();
    const uint32_t type = ctx.memoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal);
    maxBytes = std::min(maxBytes, memory.memoryHeaps[memory.memoryTypes[type].heapIndex].size);
    if (req.size > maxBytes) return false;
    return limits.maxTexelBytes == 0 ||
           vk::DeviceSize(extent.x) * extent.y * extent.z * formatBytes(format) <= limits.maxTexelBytes;
}

VolumeImage::VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                         const void* texels, std::size_t texelBytes)
    : VolumeImage(ctx, pool, dims, format, texelBytes,
                  [&](uint8_t* to) { std::memcpy(to, texels, texelBytes); }) {}

VolumeImage::VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                         std::size_t texelBytes, const TexelWriter& write)
    : format_(format), bytes_(texelBytes) {
    vk::Extent3D extent(uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z));
    auto limits = ctx.physicalDevice().getProperties().limits;
    if (std::max({extent.width, extent.height, extent.depth}) > limits.maxImageDimension3D)
        throw std::runtime_error("a volume of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                 std::to_string(dims.z) + " texels exceeds the device's 3D image limit of " +
                                 std::to_string(limits.maxImageDimension3D));
    image_ = vk::raii::Image(ctx.device(), volumeImageInfo(dims, format));
    auto req = image_.getMemoryRequirements();
    const uint32_t type = ctx.memoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal);
    memory_ = vk::raii::DeviceMemory(ctx.device(), vk::MemoryAllocateInfo(req.size, type));
    image_.bindMemory(*memory_, 0);
    // A CPU device's memory is host memory, first written by the copy below: for a 100 MB volume some 25,000 page
    // faults on 4 KiB pages, which took longer than the copy itself.
    const vk::MemoryPropertyFlags flags = ctx.physicalDevice().getMemoryProperties().memoryTypes[type].propertyFlags;
    if (ctx.info().type == "cpu" && (flags & vk::MemoryPropertyFlagBits::eHostVisible)) {
        adviseHugePages(memory_.mapMemory(0, req.size), req.size);
        memory_.unmapMemory();
    }

    HostBuffer staging(ctx, texelBytes, vk::BufferUsageFlagBits::eTransferSrc);
    adviseHugePages(staging.data(), texelBytes);
    write(static_cast<uint8_t*>(staging.data()));
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
                                      kVolumeLayout, VK_QUEUE_FAMILY_IGNORED,
                                      VK_QUEUE_FAMILY_IGNORED, *image_, range);
        cmd.pipelineBarrier(S::eTransfer, S::eComputeShader, {}, {}, {}, toRead);
    });
    view_ = vk::raii::ImageView(ctx.device(), vk::ImageViewCreateInfo({}, *image_, vk::ImageViewType::e3D, format, {},
                                                                      range));
}

}  // namespace vr
