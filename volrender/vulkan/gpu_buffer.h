// Device memory the casters use: host-visible buffers (uniforms, staging, readback) and 3D images (volumes).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

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

// A buffer in device-local memory that only shaders read and write (the ray state carried between bricks), or only
// read once filled (a table's texels).
class DeviceBuffer {
public:
    DeviceBuffer(const VulkanContext& ctx, vk::DeviceSize bytes, vk::BufferUsageFlags usage);
    // Filled with `bytes` bytes from `data` through a staging buffer, then read by compute shaders.
    DeviceBuffer(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const void* data, vk::DeviceSize bytes,
                 vk::BufferUsageFlags usage);
    const vk::raii::Buffer& buffer() const { return buffer_; }

private:
    vk::raii::Buffer buffer_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
};

// A table of four floats an entry (the transfer table, a label map's classes) as the casters read it: a storage
// texel buffer of RGBA32F texels. llvmpipe gathers a texel buffer's entries for all lanes at once, where it loads a
// storage buffer lane by lane: 4-20 % faster frames.
class TexelTable {
public:
    TexelTable(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const std::vector<float>& entries);
    const vk::raii::BufferView& view() const { return view_; }
    std::size_t bytes() const { return bytes_; }

private:
    std::size_t bytes_;
    DeviceBuffer buffer_;
    vk::raii::BufferView view_{nullptr};
};

// Lower limits than the device's for one volume image and for the transfer table (0: the device's own), so that
// tests can force bricks and refusals. The device's own: maxImageDimension3D and the format's largest extent; the
// memory the driver asks for the image (with its padding) within maxMemoryAllocationSize, the format's
// maxResourceSize and the heap; maxTexelBufferElements for the tables.
struct ImageLimits {
    uint32_t maxDimension = 0;         // texels along any axis
    vk::DeviceSize maxTexelBytes = 0;  // texels x their bytes (without the driver's padding: the same on every device)
    // Upload as on a GPU, through a staging buffer into an optimally tiled image, even where the texels could be
    // written in place (a CPU device), so that tests cover that path too.
    bool staged = false;
    vk::DeviceSize maxTableEntries = 0;  // entries of a table's texel buffer (maxTexelBufferElements)
    // At least this many bricks along each axis (at most one per voxel), whatever the images' sizes: tests split
    // volumes whose texels are too few and too small for the limits above to split them along every axis.
    Vec3i minBricks{1, 1, 1};
};

// Every volume image (scalars, fields) is a storage image, which the casters read with imageLoad: llvmpipe's
// texelFetch looks up a mip level's offset and strides lane by lane, which made the volume's fetch (then RGBA32F) a
// third of a leaping caster's time. Once uploaded it stays in this layout.
constexpr vk::ImageLayout kVolumeLayout = vk::ImageLayout::eGeneral;

// Bytes of one texel of the formats volume images use.
std::size_t formatBytes(vk::Format format);

// Whether a device-local 3D image of this extent and format can be created and allocated in one piece.
bool imageFits(const VulkanContext& ctx, const Vec3i& extent, vk::Format format, const ImageLimits& limits);

// A 3D image in device-local memory, filled once from host texels and then only read (imageLoad).
// `texels`: packed, texelBytes in all.
class VolumeImage {
public:
    // Writes the image's texels (x fastest, then y, then z) to `to`, row y of slice z at to + z * slicePitch +
    // y * rowPitch: the image's own memory on a CPU device (rows may be padded), a packed staging buffer elsewhere.
    using TexelWriter = std::function<void(uint8_t* to, std::size_t rowPitch, std::size_t slicePitch)>;

    VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                const void* texels, std::size_t texelBytes);
    VolumeImage(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Vec3i dims, vk::Format format,
                std::size_t texelBytes, const TexelWriter& write, bool staged = false);
    const vk::raii::ImageView& view() const { return view_; }
    vk::Format format() const { return format_; }
    std::size_t bytes() const { return bytes_; }  // texel bytes uploaded

private:
    vk::raii::Image image_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    vk::raii::ImageView view_{nullptr};
    vk::Format format_;
    std::size_t bytes_ = 0;
};

// Records commands into a fresh one-time command buffer, submits it and waits for it.
template <typename Record>
void submitAndWait(const VulkanContext& ctx, const vk::raii::CommandPool& pool, Record&& record) {
    vk::raii::CommandBuffers cmds(ctx.device(),
                                  vk::CommandBufferAllocateInfo(*pool, vk::CommandBufferLevel::ePrimary, 1));
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
