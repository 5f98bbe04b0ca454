// The Vulkan compute casters: same inputs and outputs as renderCpu, one dispatch per image tile.
#pragma once
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "core/prepared_volume.h"
#include "volrender/camera.h"
#include "volrender/render_result.h"
#include "volrender/vulkan/gpu_volume.h"
#include "volrender/vulkan/vulkan_context.h"

namespace vr {

class VulkanRenderer {
public:
    // Tiles of tileSize x tileSize pixels are separate submits, so no dispatch runs long enough to trip a
    // GPU watchdog.
    explicit VulkanRenderer(const VulkanContext& ctx, int tileSize = 128);

    // Uploads what the caster and the view need (see GpuVolume), renders, reads back. Throws InputError for a
    // prepared volume that lacks what the settings need, std::runtime_error for device failures (out of
    // memory, device lost) and for a ray that hit the iteration cap.
    RenderResult render(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings);

    // The resources uploaded by the last render, with their bytes.
    const std::vector<UploadedResource>& lastUploads() const { return uploads_; }

private:
    RenderResult renderOnDevice(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings);
    const vk::raii::Pipeline& pipeline(Caster caster, bool trilinear, bool shading);

    const VulkanContext& ctx_;
    int tileSize_;
    vk::raii::CommandPool pool_{nullptr};
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout pipelineLayout_{nullptr};
    vk::raii::ShaderModule shader_{nullptr};
    vk::raii::Sampler sampler_{nullptr};
    vk::raii::QueryPool queries_{nullptr};
    double timestampPeriodNs_ = 0;  // 0: the queue has no timestamps
    uint64_t timestampMask_ = 0;
    std::map<std::tuple<Caster, bool, bool>, vk::raii::Pipeline> pipelines_;
    // Bound where a variant reads nothing (normals without shading, field for primitive): never sampled.
    std::unique_ptr<VolumeImage> unusedNormals_, unusedField_;
    std::vector<UploadedResource> uploads_;
};

}  // namespace vr
