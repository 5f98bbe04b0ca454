#include "volrender/vulkan/gpu_buffer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tools/huge_pages.h"

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

DeviceBuffer::DeviceBuffer(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const void* data,
                           vk::DeviceSize bytes, vk::BufferUsageFlags usage)
    : DeviceBuffer(ctx, bytes, usage | vk::BufferUsageFlagBits::eTransferDst) {
    HostBuffer staging(ctx, bytes, vk::BufferUsageFlagBits::eTransferSrc);
    std::memcpy(staging.data(), data, bytes);
    submitAndWait(ctx, pool, [&](const vk::raii::CommandBuffer& cmd) {
        cmd.copyBuffer(*staging.buffer(), *buffer_, vk::BufferCopy(0, 0, bytes));
        vk::BufferMemoryBarrier toRead(vk::AccessFlagBits::eTransferWrite, vk::AccessFlagBits::eShaderRead,
                                       VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, *buffer_, 0, VK_WHOLE_SIZE);
        cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, {},
                            toRead, {});
    });
}

TexelTable::TexelTable(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const std::vector<float>& entries)
    : bytes_(entries.size() * sizeof(float)),
      buffer_(ctx, pool, entries.data(), bytes_, vk::BufferUsageFlagBits::eStorageTexelBuffer),
      view_(ctx.device(),
            vk::BufferViewCreateInfo({}, *buffer_.buffer(), vk::Format::eR32G32B32A32Sfloat, 0, VK_WHOLE_SIZE)) {}

namespace {

constexpr vk::ImageUsageFlags kVolumeUsage = vk::ImageUsageFlagBits::eStorage | vk::ImageUsageFlagBits::eTransferDst;
constexpr vk::MemoryPropertyFlags kHostWritable = vk::MemoryPropertyFlagBits::eDeviceLocal |
                                                  vk::MemoryPropertyFlagBits::eHostVisible |
                                                  vk::MemoryPropertyFlagBits::eHostCoherent;

// A CPU device's image memory is host memory: its texels are written there in place, through linear tiling
// (llvmpipe lays out optimal images linearly too), without a staging buffer and a copy. That halves the memory an
// upload first touches, which on this project's VM costs more than the copying. Elsewhere, or when `staged`:
// optimal tiling, through a staging buffer.
vk::ImageTiling volumeTiling(const VulkanContext& ctx, const Vec3i& extent, vk::Format format, bool staged) {
    const vk::raii::PhysicalDevice& gpu = ctx.physicalDevice();
    const auto memory = gpu.getMemoryProperties();
    const bool hostMemory =
        !staged && ctx.info().type == "cpu" &&
        std::any_of(memory.memoryTypes.begin(), memory.memoryTypes.begin() + memory.memoryTypeCount,
                    [](const vk::MemoryType& t) { return (t.propertyFlags & kHostWritable) == kHostWritable; });
    if (!hostMemory) return vk::ImageTiling::eOptimal;
    try {
        const vk::ImageFormatProperties linear =
            gpu.getImageFormatProperties(format, vk::ImageType::e3D, vk::ImageTiling::eLinear, kVolumeUsage);
        const vk::Extent3D& max = linear.maxExtent;
        if (uint32_t(extent.x) <= max.width && uint32_t(extent.y) <= max.height && uint32_t(extent.z) <= max.depth)
            return vk::ImageTiling::eLinear;
    } catch (const vk::FormatNotSupportedError&) {
    }
    return vk::ImageTiling::eOptimal;
}

vk::ImageCreateInfo volumeImageInfo(const Vec3i& dims, vk::Format format, vk::ImageTiling tiling) {
    // Linear images keep what the host writes before their first use (preinitialized).
    return vk::ImageCreateInfo({}, vk::ImageType::e3D, format,
                               vk::Extent3D(uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z)), 1, 1,
                               vk::SampleCountFlagBits::e1, tiling, kVolumeUsage, vk::SharingMode::eExclusive, {},
                               tiling == vk::ImageTiling::eLinear ? vk::ImageLayout::ePreinitialized
                                                                  : vk::ImageLayout::eUndefined);
}

}  // namespace

std::size_t formatBytes(vk::Format format) {
    switch (format) {
        case vk::Format::eR8Uint: return 1;
        case vk::Format::eR16Uint: return 2;
        case vk::Format::eR16Sint: return 2;
        case vk::Format::eR32Sfloat: return 4;
        case vk::Format::eR32Uint: return 4;
        case vk::Format::eR32G32Sfloat: return 8;
        case vk::Format::eR8G8B8A8Uint: return 4;
        default: throw std::logic_error("formatBytes: a volume image format without its size here");
    }
}

bool imageFits(const VulkanContext& ctx, const Vec3i& extent, vk::Format format, const ImageLimits& limits) {
    const vk::raii::PhysicalDevice& gpu = ctx.physicalDevice();
    uint32_t maxDimension = gpu.getProperties().limits.maxImageDimension3D;
    if (limits.maxDimension > 0) maxDimension = std::min(maxDimension, limits.maxDimension);
    const vk::ImageTiling tiling = volumeTiling(ctx, extent, format, limits.staged);
    vk::ImageFormatProperties format3d;
    try {
        format3d = gpu.getImageFormatProperties(format, vk::ImageType::e3D, tiling, kVolumeUsage);
    } catch (const vk::FormatNotSupportedError&) {
        return false;
    }
    for (int a = 0; a < 3; ++a) {
        const uint32_t formatMax = a == 0 ? format3d.maxExtent.width : a == 1 ? format3d.maxExtent.height
                                                                              : format3d.maxExtent.depth;
        if (extent[a] < 1 || uint32_t(extent[a]) > std::min(maxDimension, formatMax)) return false;
    }
    // The memory the driver asks for, with its padding, against one allocation's limits.
    const vk::raii::Image probe(ctx.device(), volumeImageInfo(extent, format, tiling));
    const vk::MemoryRequirements req = probe.getMemoryRequirements();
    const auto props = gpu.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceMaintenance3Properties>();
    vk::DeviceSize maxBytes = std::min(props.get<vk::PhysicalDeviceMaintenance3Properties>().maxMemoryAllocationSize,
                                       format3d.maxResourceSize);
    const auto memory = gpu.getMemoryProperties();
    const uint32_t type = ctx.memoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal);
    maxBytes = std::min(maxBytes, memory.memoryHeaps[memory.memoryTypes[type].heapIndex].size);
    if (req.size > maxBytes) return false;
    return limits.maxTexelBytes == 0 ||
           vk::DeviceSize(extent.x) * extent.y * extent.z * formatBytes(format) <= limits.maxTexelBytes;
}

VolumeImage::VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                         const void* texels, std::size_t texelBytes)
    : VolumeImage(ctx, pool, dims, format, texelBytes, [&](uint8_t* to, std::size_t rowPitch, std::size_t slicePitch) {
          const std::size_t row = std::size_t(dims.x) * formatBytes(format);
          const auto* from = static_cast<const uint8_t*>(texels);
          for (int z = 0; z < dims.z; ++z)
              for (int y = 0; y < dims.y; ++y, from += row) std::memcpy(to + z * slicePitch + y * rowPitch, from, row);
      }) {}

VolumeImage::VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                         std::size_t texelBytes, const TexelWriter& write, bool staged)
    : format_(format), bytes_(texelBytes) {
    vk::Extent3D extent(uint32_t(dims.x), uint32_t(dims.y), uint32_t(dims.z));
    auto limits = ctx.physicalDevice().getProperties().limits;
    if (std::max({extent.width, extent.height, extent.depth}) > limits.maxImageDimension3D)
        throw std::runtime_error("a volume of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                 std::to_string(dims.z) + " texels exceeds the device's 3D image limit of " +
                                 std::to_string(limits.maxImageDimension3D));
    const vk::ImageTiling tiling = volumeTiling(ctx, dims, format, staged);
    const bool inPlace = tiling == vk::ImageTiling::eLinear;
    image_ = vk::raii::Image(ctx.device(), volumeImageInfo(dims, format, tiling));
    auto req = image_.getMemoryRequirements();
    const uint32_t type = inPlace ? ctx.memoryType(req.memoryTypeBits, kHostWritable)
                                  : ctx.memoryType(req.memoryTypeBits, vk::MemoryPropertyFlagBits::eDeviceLocal);
    memory_ = vk::raii::DeviceMemory(ctx.device(), vk::MemoryAllocateInfo(req.size, type));
    image_.bindMemory(*memory_, 0);
    const std::size_t row = std::size_t(dims.x) * formatBytes(format), slice = row * dims.y;
    vk::ImageSubresourceRange range(vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1);
    using A = vk::AccessFlagBits;
    using S = vk::PipelineStageFlagBits;
    if (inPlace) {
        auto* mapped = static_cast<uint8_t*>(memory_.mapMemory(0, req.size));
        // Fresh host memory: some 25,000 page faults per 100 MB on 4 KiB pages, more than the writing itself.
        adviseHugePages(mapped, req.size);
        const vk::SubresourceLayout layout =
            image_.getSubresourceLayout(vk::ImageSubresource(vk::ImageAspectFlagBits::eColor, 0, 0));
        write(mapped + layout.offset, layout.rowPitch, layout.depthPitch);
        memory_.unmapMemory();
        submitAndWait(ctx, pool, [&](const vk::raii::CommandBuffer& cmd) {
            vk::ImageMemoryBarrier toRead(A::eHostWrite, A::eShaderRead, vk::ImageLayout::ePreinitialized,
                                          kVolumeLayout, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, *image_,
                                          range);
            cmd.pipelineBarrier(S::eHost, S::eComputeShader, {}, {}, {}, toRead);
        });
    } else {
        HostBuffer staging(ctx, texelBytes, vk::BufferUsageFlagBits::eTransferSrc);
        adviseHugePages(staging.data(), texelBytes);
        write(static_cast<uint8_t*>(staging.data()), row, slice);
        submitAndWait(ctx, pool, [&](const vk::raii::CommandBuffer& cmd) {
            vk::ImageMemoryBarrier toDst({}, A::eTransferWrite, vk::ImageLayout::eUndefined,
                                         vk::ImageLayout::eTransferDstOptimal, VK_QUEUE_FAMILY_IGNORED,
                                         VK_QUEUE_FAMILY_IGNORED, *image_, range);
            cmd.pipelineBarrier(S::eTopOfPipe, S::eTransfer, {}, {}, {}, toDst);
            vk::BufferImageCopy copy(0, 0, 0, vk::ImageSubresourceLayers(vk::ImageAspectFlagBits::eColor, 0, 0, 1),
                                     {0, 0, 0}, extent);
            cmd.copyBufferToImage(*staging.buffer(), *image_, vk::ImageLayout::eTransferDstOptimal, copy);
            vk::ImageMemoryBarrier toRead(A::eTransferWrite, A::eShaderRead, vk::ImageLayout::eTransferDstOptimal,
                                          kVolumeLayout, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, *image_,
                                          range);
            cmd.pipelineBarrier(S::eTransfer, S::eComputeShader, {}, {}, {}, toRead);
        });
    }
    view_ = vk::raii::ImageView(ctx.device(), vk::ImageViewCreateInfo({}, *image_, vk::ImageViewType::e3D, format, {},
                                                                      range));
}

}  // namespace vr
