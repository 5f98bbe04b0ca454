// A prepared volume on the device: only what its renders need (docs/ALGORITHMS.md section 4, storage), split into
// bricks where one image would exceed the device's limits. Upload once, render many views (VulkanRenderer).
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "render/render_settings.h"
#include "volrender/vulkan/brick_grid.h"
#include "volrender/vulkan/gpu_buffer.h"

namespace vr {

struct UploadedResource {
    std::string name;  // "classified", "normals", "pc", "acd", "eacd"
    std::size_t bytes = 0;
    int brick = 0;     // index into GpuVolume::bricks()
};

// What one upload holds: the fields of these casters (none for primitive), normals when shading, and the ACD /
// EACD octants of the mask (viewOctants of every camera it will render).
struct GpuVolumeContents {
    std::vector<Caster> casters;
    bool shading = true;
    unsigned octants = 0;
};

class GpuVolume {
public:
    // Uploads the classified volume (rgb + sigma, RGBA32F), the normals (RGBA16_SNORM) only when shading, and
    // each caster's field: PC (R8_UINT), ACD (R8_UINT), EACD (RGBA8_UINT exact, R16_UINT log16, R8_UINT joint8);
    // ACD and EACD hold the octants of the mask stacked along z, slab i holding the i-th octant of the mask.
    // Each image is split into the bricks of one plan that fits every image.
    // Throws InputError when the prepared volume lacks a field or the normals asked for.
    GpuVolume(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const PreparedVolume& prepared,
              const GpuVolumeContents& contents, const ImageLimits& limits = {});

    const GridGeometry& grid() const { return grid_; }
    const GpuVolumeContents& contents() const { return contents_; }
    const BrickGrid& bricks() const { return bricks_; }
    const VolumeImage& classified(int brick) const { return *classified_[brick]; }
    const VolumeImage* normals(int brick) const { return normals_.empty() ? nullptr : normals_[brick].get(); }
    // Null for primitive or a caster not uploaded.
    const VolumeImage* field(Caster caster, int brick) const;
    // Slab of each octant in the ACD / EACD images, -1 when not uploaded.
    const std::array<int, kOctants>& octantSlot() const { return slot_; }
    // How the EACD image holds the extents (RGBA8 exact, R16 log16, R8 joint8; see core/extent_code.h).
    ExtentCode eacdCode() const { return eacdCode_; }
    const std::vector<UploadedResource>& uploads() const { return uploads_; }
    std::size_t uploadedBytes() const;

    bool segmentedForTrilinear() const { return segmentedForTrilinear_; }
    // Throws std::invalid_argument naming what is missing when a render with these settings and view octants
    // would need more than was uploaded.
    void requireHolds(const RenderSettings& settings, unsigned viewOctants) const;

private:
    using Bricked = std::vector<std::unique_ptr<VolumeImage>>;  // one image per brick
    GridGeometry grid_;
    GpuVolumeContents contents_;
    ExtentCode eacdCode_ = ExtentCode::Exact;
    bool segmentedForTrilinear_ = false;
    BrickGrid bricks_;
    Bricked classified_, normals_;
    std::array<Bricked, 4> fields_;  // by Caster
    std::array<int, kOctants> slot_;
    std::vector<UploadedResource> uploads_;
};

}  // namespace vr
