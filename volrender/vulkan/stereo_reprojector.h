// The reprojection of a stereo pair's left eye into its right eye on the device (shaders/stereo_reproject.comp).
#pragma once
#include "shaders/stereo_reprojection.h"
#include "volrender/vulkan/device_timer.h"
#include "volrender/vulkan/gpu_buffer.h"

namespace vr {

// The format of a stereo left eye's band segments (shaders/stereo_reprojection.h packBandSegment).
constexpr vk::Format kBandSegmentFormat = vk::Format::eR32G32B32A32Uint;

class StereoReprojector {
public:
    StereoReprojector(const VulkanContext& ctx, const vk::raii::CommandPool& pool);

    // Reads the left eye's pixels (device::OutPixel each, row by row) or, for composite, its bands' segments
    // (`bands`, a layer per band), writes the reprojected right eye (OutPixel each) and appends
    // the right pixels it cannot vouch for to `recast` (its count, then the packed pixels; the count must start at
    // 0). Returns the device milliseconds it took (0 where the queue has no timestamps).
    double reproject(const vk::raii::CommandPool& pool, const device::StereoParams& params, const HostBuffer& left,
                     const ShaderImage* bands, const HostBuffer& right, const HostBuffer& recast);

private:
    const VulkanContext& ctx_;
    DeviceTimer timer_;
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout layout_{nullptr};
    vk::raii::ShaderModule shader_{nullptr};
    vk::raii::Pipeline intervals_{nullptr}, bands_{nullptr};  // the shader without and with its bands constant
    ShaderImage unusedBands_;                                 // bound without bands
};

}  // namespace vr
