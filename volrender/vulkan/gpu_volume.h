// A prepared volume on the device: only what its renders need (docs/ALGORITHMS.md section 4, storage), split into
// bricks where one image would exceed the device's limits. Upload once, render many views (VulkanRenderer).
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/prepared_volume.h"
#include "render/flat_table_ends.h"
#include "render/render_settings.h"
#include "shaders/blend.h"
#include "volrender/vulkan/brick_grid.h"
#include "volrender/vulkan/gpu_buffer.h"

namespace vr {

struct UploadedResource {
    std::string name;  // "scalars", "table", "label map", "label table", "gradients", "pc", "acd", "eacd", "blocks",
                       // "hier"
    std::size_t bytes = 0;
    int brick = 0;     // index into GpuVolume::bricks(); the table, which every brick reads, counts as brick 0's
};

// What one upload holds besides the scalars and the transfer table, which every render reads: the fields of these
// casters (none for primitive; the block extrema for blocks) and the ACD / EACD octants of the mask (viewOctants of
// every camera it will render). Shading by central differences needs nothing more; shading by stored gradients needs
// them uploaded.
struct GpuVolumeContents {
    std::vector<Caster> casters;
    unsigned octants = 0;
    bool gradients = false;  // each voxel's stored gradient (render/stored_gradients.h), R32_UINT
};

constexpr vk::Format kGradientFormat = vk::Format::eR32Uint;
// Integer scalars and labels, packed along x into 32-bit words (shaders/device_contract.h wordShift).
constexpr vk::Format kWordFormat = vk::Format::eR32Uint;
// The hier field's blocks of 2^shift voxels that the voxels imageLo .. imageLo + imageDims - 1 of a brick's images
// touch: the first and their count per axis (shaders/brick_state.glsl blockTexel reads them so).
struct BrickBlocks {
    Vec3i lo, count;
};
BrickBlocks brickBlocks(const Vec3i& imageLo, const Vec3i& imageDims, int shift);

// The block extrema's format: RG32F, a block's lo and hi in one texel (render/block_extrema.h's texels), so that
// the blocks caster reads a block's range with one image load (llvmpipe gathers each load's lanes).
constexpr vk::Format kBlockExtremaFormat = vk::Format::eR32G32Sfloat;

// The storage-image format of the scalars of each type: R32_UINT words packing integers along x (device_contract.h
// wordShift), or R32_SFLOAT; and how many scalars a texel holds along x.
vk::Format scalarFormat(ScalarType type);
int scalarsPerTexel(ScalarType type);

// Every format the casters read as a storage image: the scalars' two and the fields' (R8_UINT, R16_UINT,
// RGBA8_UINT), with their names and what each holds, for messages.
struct CasterImageFormat {
    vk::Format format;
    const char* name;   // "R32_UINT"
    const char* holds;  // "integer scalars and labels, in words, and stored gradients"
};
const std::vector<CasterImageFormat>& casterImageFormats();

// Throws std::runtime_error naming what the device `deviceName` lacks of what the casters read: the feature
// shaderStorageImageExtendedFormats (R8_UINT and R16_UINT storage images) and, for every format of
// casterImageFormats(), VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT with optimal tiling. The device's answers come as
// arguments, so that tests can ask it of devices that lack them.
void requireCasterImageSupport(const std::string& deviceName, const vk::PhysicalDeviceFeatures& features,
                               const std::function<vk::FormatProperties(vk::Format)>& formatProperties);

// Where the transfer table's entries lie in scalar, when a gradient is flat and the length of the TF's opacity:
// what the casters need of ScalarClassification besides the entries themselves, which are on the device.
struct TablePlacement {
    double lo = 0, step = 1;
    std::size_t entries = 0;
    double flatGradient = 0;
    double referenceStep = 1;
    // Where MIP and MinIP rays start and end: shown through the entries' opacity, and opaque (a grey window).
    FlatTableEnds flat, opaqueFlat;
};

class GpuVolume {
public:
    // Uploads the scalars in their own type (scalarFormat), the transfer table (a TexelTable, an entry per texel:
    // rgb colour, sigma), a label map's labels in their type, packed as integer scalars, and its table (as the
    // transfer table) and each caster's field: PC (R8_UINT), ACD (R8_UINT), EACD (RGBA8_UINT exact, R16_UINT log16,
    // R8_UINT joint8), hier (R16_UINT, one image of the blocks); ACD, EACD and hier hold the octants of the mask
    // stacked along z, slab i holding the i-th octant of the mask. Each image is split into the bricks of one plan
    // that fits every image.
    // Throws InputError when the prepared volume lacks a field asked for, its scalars do not fit their type, or
    // a table has more entries than the device's texel buffers hold (maxTexelBufferElements).
    GpuVolume(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const PreparedVolume& prepared,
              const GpuVolumeContents& contents, const ImageLimits& limits = {});

    const GridGeometry& grid() const { return grid_; }
    const GpuVolumeContents& contents() const { return contents_; }
    const BrickGrid& bricks() const { return bricks_; }
    ScalarType scalarType() const { return scalarType_; }
    const VolumeImage& scalars(int brick) const { return *scalars_[brick]; }
    // The label map's labels (R8_UINT or R16_UINT as its type) and its table (vec4 per label: rgb colour, sigma);
    // null without a label map.
    bool labelled() const { return labelTable_ != nullptr; }
    ScalarType labelType() const { return labelType_; }
    const VolumeImage* labels(int brick) const { return labels_.empty() ? nullptr : labels_[brick].get(); }
    const TexelTable* labelTable() const { return labelTable_.get(); }
    int labelLastEntry() const { return labelLastEntry_; }
    const TexelTable& table() const { return *table_; }
    const TablePlacement& tablePlacement() const { return placement_; }
    // Each voxel's stored gradient, null when not uploaded; the codes' base exponent.
    const VolumeImage* gradients(int brick) const { return gradients_.empty() ? nullptr : gradients_[brick].get(); }
    int gradientExponentBase() const { return gradientBase_; }
    // Null for primitive, blocks or a caster not uploaded. A brick's hier image holds the blocks its images' voxels
    // touch (brickBlocks), the octants' slabs stacked along z.
    const VolumeImage* field(Caster caster, int brick) const;
    // The hier field's blocks are 1 << hierBlockShift() voxels per axis.
    int hierBlockShift() const { return hierBlockShift_; }
    // Each block's scalar range, one image for every brick (in whole-volume blocks); null when not uploaded.
    const VolumeImage* blockExtrema() const { return blockExtrema_.get(); }
    // The first z texel of each level of blocks in that image.
    const std::array<int, device::kBlockLevels>& blockLevelZ() const { return blockLevelZ_; }
    // Slab of each octant in the ACD / EACD images, -1 when not uploaded.
    const std::array<int, kOctants>& octantSlot() const { return slot_; }
    // How the EACD image holds the extents (RGBA8 exact, R16 log16, R8 joint8; see core/extent_code.h).
    ExtentCode eacdCode() const { return eacdCode_; }
    const std::vector<UploadedResource>& uploads() const { return uploads_; }
    std::size_t uploadedBytes() const;

    // How the regions were segmented (for trilinear sampling, with normals): what a render's checks ask.
    const SegmentationParams& segmentation() const { return segmentation_; }
    // Throws std::invalid_argument naming what is missing when a render with these settings and view octants
    // would need more than was uploaded.
    void requireHolds(const RenderSettings& settings, unsigned viewOctants) const;

private:
    using Bricked = std::vector<std::unique_ptr<VolumeImage>>;  // one image per brick
    GridGeometry grid_;
    GpuVolumeContents contents_;
    ScalarType scalarType_ = ScalarType::Float32;
    ExtentCode eacdCode_ = ExtentCode::Exact;
    SegmentationParams segmentation_;
    TablePlacement placement_;
    BrickGrid bricks_;
    Bricked scalars_;
    std::unique_ptr<TexelTable> table_;
    Bricked labels_;
    std::unique_ptr<TexelTable> labelTable_;
    ScalarType labelType_ = ScalarType::UInt8;
    int labelLastEntry_ = 0;
    Bricked gradients_;
    int gradientBase_ = 0;
    std::array<Bricked, 4> fields_;  // by Caster, but blocks
    std::unique_ptr<VolumeImage> blockExtrema_;
    Bricked hier_;
    int hierBlockShift_ = 0;
    std::array<int, device::kBlockLevels> blockLevelZ_{};
    std::array<int, kOctants> slot_;
    std::vector<UploadedResource> uploads_;
};

}  // namespace vr
