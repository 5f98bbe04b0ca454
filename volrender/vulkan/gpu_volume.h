// A prepared volume on the device: only what one caster and one view need (ALGORITHMS.md section 4, storage).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "volrender/render_settings.h"
#include "volrender/vulkan/gpu_buffer.h"

namespace vr {

struct UploadedResource {
    std::string name;  // "classified", "normals", "pc", "acd", "eacd"
    std::size_t bytes = 0;
};

class GpuVolume {
public:
    // Uploads the classified volume (rgb + sigma, RGBA32F), the normals (RGBA16_SNORM) only when shading, and
    // the caster's field: none for primitive, PC (R8_UINT), or the octants in `octants` of ACD (R8_UINT) /
    // EACD (RGBA8_UINT, the 4th byte unused), stacked along z, slab i holding the i-th octant of the mask.
    GpuVolume(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const PreparedVolume& prepared,
              Caster caster, bool shading, unsigned octants);

    const VolumeImage& classified() const { return *classified_; }
    const VolumeImage* normals() const { return normals_.get(); }  // null without shading
    const VolumeImage* field() const { return field_.get(); }      // null for primitive
    // Slab of each octant in field(), -1 when not uploaded.
    const std::array<int, kOctants>& octantSlot() const { return slot_; }
    const std::vector<UploadedResource>& uploads() const { return uploads_; }

private:
    std::unique_ptr<VolumeImage> classified_, normals_, field_;
    std::array<int, kOctants> slot_;
    std::vector<UploadedResource> uploads_;
};

}  // namespace vr
