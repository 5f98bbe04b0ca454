// The Vulkan compute casters: same inputs and outputs as renderCpu, one dispatch per image tile and brick.
#pragma once
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "core/prepared_volume.h"
#include "render/camera.h"
#include "render/render_result.h"
#include "volrender/vulkan/gpu_volume.h"
#include "volrender/vulkan/vulkan_context.h"

namespace vr {

class VulkanRenderer {
public:
    // Tiles of tileSize x tileSize pixels are separate submits, so no dispatch runs long enough to trip a
    // GPU watchdog; kAutoTile: 1024 on a GPU (smaller tiles leave most of a large GPU idle), or 512 on a CPU
    // device (no watchdog; each submit costs llvmpipe a thread-pool round). `limits` lowers the device's image and
    // storage-buffer limits (tests force bricks and refusals with it). Throws std::runtime_error for a device that
    // cannot read the casters' storage-image formats (requireCasterImageSupport).
    static constexpr int kAutoTile = 0;
    explicit VulkanRenderer(const VulkanContext& ctx, int tileSize = kAutoTile, const ImageLimits& limits = {});
    int tileSize() const { return tileSize_; }

    // Uploads a prepared volume once for many renders (see GpuVolume); a volume too large for one image is split
    // into bricks. Throws InputError when the prepared volume lacks what `contents` asks for.
    GpuVolume upload(const PreparedVolume& prepared, const GpuVolumeContents& contents);

    // Renders an uploaded volume, reads back. Throws InputError for unusable settings, std::invalid_argument when
    // the volume lacks what the settings or the view need, std::runtime_error for device failures (out of memory,
    // device lost) and for a ray that hit the iteration cap.
    RenderResult render(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings);

    // Uploads just what this caster and view need, then renders (one-off renders; an orbit uploads once).
    RenderResult render(const PreparedVolume& prepared, const Camera& camera, const RenderSettings& settings);

    // The resources the last render read (of the volume uploaded for it or given to it), per brick: the scalars,
    // the transfer table, the caster's field.
    const std::vector<UploadedResource>& lastUploads() const { return uploads_; }

private:
    RenderResult renderOnDevice(const GpuVolume& volume, const Camera& camera, const RenderSettings& settings);
    // bricked: the volume is split into bricks, whose dispatches carry each ray's state to the next.
    // labels: the device's label type (device::kNoLabels without a label map).
    const vk::raii::Pipeline& pipeline(Caster caster, Blend blend, bool trilinear, bool shading, ExtentCode eacdCode,
                                       bool bricked, bool perspective, ScalarType scalarType, int labels);
    // Turns Vulkan's out-of-memory and device-lost errors into messages that say what to try.
    template <typename Work>
    auto deviceErrors(Work&& work) -> decltype(work());

    const VulkanContext& ctx_;
    int tileSize_;
    ImageLimits limits_;
    vk::raii::CommandPool pool_{nullptr};
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout pipelineLayout_{nullptr};
    vk::raii::ShaderModule shader_{nullptr};
    vk::raii::QueryPool queries_{nullptr};
    double timestampPeriodNs_ = 0;  // 0: the queue has no timestamps
    uint64_t timestampMask_ = 0;
    std::map<std::tuple<Caster, Blend, bool, bool, ExtentCode, bool, bool, ScalarType, int>, vk::raii::Pipeline>
        pipelines_;
    // Bound where a variant reads nothing (the scalar bindings of the other types, the field for primitive, the
    // field bindings of the other formats, the block extrema for every caster but blocks, the label bindings of a
    // volume without labels or of the other label type): never read.
    std::unique_ptr<VolumeImage> unusedScalars_[4], unusedFields_[3], unusedBlockExtrema_, unusedLabels_[2];
    std::unique_ptr<DeviceBuffer> unusedLabelTable_;  // bound without a label map
    std::vector<UploadedResource> uploads_;
};

}  // namespace vr
