// The reprojection of a stereo pair's left eye into its right eye on the device (shaders/stereo_reproject.comp).
#pragma once
#include <mutex>

#include "shaders/stereo_reprojection.h"
#include "volrender/vulkan/device_timer.h"
#include "volrender/vulkan/gpu_buffer.h"

namespace vr {

// A stereo left eye's band segments: a storage buffer the casters write (uvec4 each), a texel buffer of this format
// the reprojection reads (shaders/stereo_reprojection.h packBandSegment).
constexpr vk::Format kBandSegmentFormat = vk::Format::eR32G32B32A32Uint;
constexpr vk::BufferUsageFlags kBandSegmentUsage =
    vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eStorageTexelBuffer;

class StereoReprojector {
public:
    explicit StereoReprojector(const VulkanContext& ctx);

    // Reads the left eye's pixels (device::OutPixel each, row by row) or, for composite, its bands' segments
    // (`bands`: kBandSegmentUsage), writes the reprojected right eye's colours (a uvec4 of float bits each) and
    // appends the right eye's rays it cannot vouch for to `recast` (its count, then a device::ListRay each: the
    // pixel, and where its ray starts behind what the reprojection vouches for; the count must start at 0). Returns
    // the device milliseconds it took (0 where the queue has no timestamps).
    double reproject(const vk::raii::CommandPool& pool, const device::StereoParams& params, const HostBuffer& left,
                     const DeviceBuffer* bands, const HostBuffer& right, const HostBuffer& recast);

    // Makes, ahead of a pair, the pipeline that reproject() takes with bands (composite) or without (the other
    // blends). Safe beside a reprojection on another thread, which waits for a pipeline being made.
    void preparePipeline(bool bands) { pipeline(bands); }
    // How many of its two pipelines it has made.
    int pipelineCount();

private:
    // The shader without or with its bands constant, made at first use: a CPU device takes tens of ms over one.
    const vk::raii::Pipeline& pipeline(bool bands);

    const VulkanContext& ctx_;
    DeviceTimer timer_;
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout layout_{nullptr};
    vk::raii::ShaderModule shader_{nullptr};
    vk::raii::Pipeline intervals_{nullptr}, bands_{nullptr};
    std::mutex pipelinesMutex_;  // held while a pipeline is looked up or made
    DeviceBuffer unusedBands_;   // bound without bands
};

}  // namespace vr
