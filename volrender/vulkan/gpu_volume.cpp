#include "volrender/vulkan/gpu_volume.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <functional>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/errors.h"
#include "render/block_extrema.h"
#include "render/render_checks.h"
#include "render/stored_gradients.h"
#include "shaders/device_contract.h"

namespace vr {
namespace {

// One image of the whole volume, waiting for the brick plan that every image of the volume fits. Its texels are
// written row by row straight into each brick's image (or staging) memory: a copy of the whole image first, in
// fresh memory, cost more than the upload itself (page faults on every new page, then a second copy).
struct WholeImage {
    std::vector<std::unique_ptr<VolumeImage>>* bricks;
    const char* name;
    int slabs;  // z-slabs of the volume's depth stacked in the image (ACD / EACD: one per octant)
    vk::Format format;
    // Writes `count` texels of slab `slab`, from voxel `first` (a linear index) along x, to `to`.
    std::function<void(int slab, std::size_t first, int count, uint8_t* to)> row;
    int perTexel = 1;  // voxels along x a texel holds: the row's texels in words of integers (device_contract.h)

    // The texels of a box of `voxels`: its rows in texels, its slabs stacked along z.
    Vec3i extent(const Vec3i& voxels) const {
        return {(voxels.x + perTexel - 1) / perTexel, voxels.y, voxels.z * slabs};
    }
};

// The casters whose fields hold one slab per octant.
bool usesOctants(Caster c) { return c == Caster::ACD || c == Caster::EACD || c == Caster::Hier; }

// EACD texels: exact extents in RGB (A unused), or the code that the shader decodes through its table.
vk::Format eacdFormat(ExtentCode code) {
    switch (code) {
        case ExtentCode::Exact: return vk::Format::eR8G8B8A8Uint;
        case ExtentCode::Log16: return vk::Format::eR16Uint;
        case ExtentCode::Joint8: return vk::Format::eR8Uint;
    }
    return vk::Format::eUndefined;
}

}  // namespace

BrickBlocks brickBlocks(const Vec3i& imageLo, const Vec3i& imageDims, int shift) {
    BrickBlocks b;
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = imageLo[a] >> shift;
        b.count[a] = ((imageLo[a] + imageDims[a] - 1) >> shift) - b.lo[a] + 1;
    }
    return b;
}

vk::Format scalarFormat(ScalarType type) {
    return type == ScalarType::Float32 ? vk::Format::eR32Sfloat : kWordFormat;
}

int scalarsPerTexel(ScalarType type) { return 1 << device::wordShift(int(8 * scalarBytes(type))); }

const std::vector<CasterImageFormat>& casterImageFormats() {
    static const std::vector<CasterImageFormat> formats{
        {kWordFormat, "R32_UINT", "integer scalars and labels, in words, and stored gradients"},
        {scalarFormat(ScalarType::Float32), "R32_SFLOAT", "float32 scalars and the blocks caster's scalar ranges"},
        {vk::Format::eR8Uint, "R8_UINT", "PC, ACD and joint8 EACD"},
        {eacdFormat(ExtentCode::Log16), "R16_UINT", "log16 EACD"},
        {eacdFormat(ExtentCode::Exact), "R8G8B8A8_UINT", "exact EACD"}};
    return formats;
}

void requireCasterImageSupport(const std::string& deviceName, const vk::PhysicalDeviceFeatures& features,
                               const std::function<vk::FormatProperties(vk::Format)>& formatProperties) {
    if (!features.shaderStorageImageExtendedFormats)
        throw std::runtime_error("the Vulkan device " + deviceName +
                                 " lacks the feature shaderStorageImageExtendedFormats, which the casters need to "
                                 "read R8_UINT and R16_UINT storage images");
    for (const CasterImageFormat& f : casterImageFormats())
        if (!(formatProperties(f.format).optimalTilingFeatures & vk::FormatFeatureFlagBits::eStorageImage))
            throw std::runtime_error("the Vulkan device " + deviceName + " cannot use " + f.name +
                                     " as a storage image (VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT), which the casters "
                                     "need for " + f.holds);
}

GpuVolume::GpuVolume(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const PreparedVolume& prepared,
                     const GpuVolumeContents& contents, const ImageLimits& limits)
    : grid_(prepared.grid()), contents_(contents), scalarType_(prepared.scalars.sourceType),
      eacdCode_(prepared.fields.eacdCode()), segmentation_(prepared.meta.segmentation) {
    slot_.fill(-1);
    const unsigned octants = contents.octants;
    // The scalars and the table (every render's), then each caster's field. Shading is the render's choice: it
    // needs nothing uploaded.
    std::vector<Caster> checked{Caster::Primitive};
    checked.insert(checked.end(), contents.casters.begin(), contents.casters.end());
    for (Caster caster : checked) {
        RenderSettings needs;
        needs.caster = caster;
        needs.blend = caster == Caster::Blocks ? Blend::MIP : Blend::Composite;  // one blend the caster serves
        needs.shading = false;
        checkRenderInputs(prepared, needs);
        if (usesOctants(caster) && (octants & kAllOctants) == 0)
            throw std::invalid_argument("uploading the " + std::string(casterName(caster)) + " field needs octants");
        const unsigned held = caster == Caster::ACD    ? prepared.fields.acdOctants()
                              : caster == Caster::EACD ? prepared.fields.eacdOctants()
                              : caster == Caster::Hier ? prepared.fields.hier.octants()
                                                       : kAllOctants;
        if ((octants & kAllOctants & ~held) != 0)
            throw InputError("the views need octants the " + std::string(casterName(caster)) +
                             " field was not built for (mask " + std::to_string(octants & ~held) + ")");
    }

    // The table first: a device whose texel buffers cannot hold it is refused before any image is made.
    const ScalarClassification& classification = prepared.classification;
    const TransferTable& table = classification.table;
    placement_ = {table.lo, table.step, table.size(), classification.flatGradient, classification.referenceStep,
                  flatTableEnds(table, false), flatTableEnds(table, true)};
    vk::DeviceSize maxEntries = ctx.physicalDevice().getProperties().limits.maxTexelBufferElements;
    if (limits.maxTableEntries > 0) maxEntries = std::min(maxEntries, limits.maxTableEntries);
    const auto tableFits = [&](const std::string& what, std::size_t entries) {
        if (entries > maxEntries)
            throw InputError(what + " of " + std::to_string(entries) + " entries exceeds the texel buffer limit of the "
                             "Vulkan device " + ctx.info().name + " (maxTexelBufferElements " +
                             std::to_string(maxEntries) + ": at most " + std::to_string(maxEntries) +
                             " entries); render with --cpu");
    };
    tableFits("the transfer table", table.size());
    table_ = std::make_unique<TexelTable>(ctx, pool, table.interleaved());
    uploads_.push_back({"table", table_->bytes(), 0});

    const Vec3i dims = grid_.dims;
    const Volume& scalars = prepared.scalars;
    std::atomic<bool> scalarsFit = true;
    std::vector<WholeImage> wholes;
    const ScalarType scalarType = scalarType_;
    const auto scalarRow = [&scalars, &scalarsFit, scalarType](int, std::size_t first, int count, uint8_t* to) {
        const std::size_t bytes = scalarBytes(scalarType);
        if (scalars.values.empty())  // held in their own type: copied as they are
            std::memcpy(to, scalars.stored.data() + first * bytes, std::size_t(count) * bytes);
        else if (narrowScalars(scalars.values.data() + first, std::size_t(count), scalarType, to) < std::size_t(count))
            scalarsFit = false;
    };
    wholes.push_back({&scalars_, "scalars", 1, scalarFormat(scalarType_), scalarRow, scalarsPerTexel(scalarType_)});
    if (const std::optional<LabelMap>& labels = prepared.labels) {
        tableFits("the label table", labels->classes.size());
        labelTable_ = std::make_unique<TexelTable>(ctx, pool, labels->classes.interleaved());
        uploads_.push_back({"label table", labelTable_->bytes(), 0});
        labelType_ = labels->type;
        labelLastEntry_ = labels->lastEntry();
        const std::vector<uint16_t>& l = labels->label;
        const bool wide = labelType_ == ScalarType::UInt16;
        wholes.push_back({&labels_, "label map", 1, kWordFormat,
                          [&l, wide](int, std::size_t first, int count, uint8_t* to) {
                              if (wide) std::memcpy(to, l.data() + first, std::size_t(count) * sizeof(uint16_t));
                              else for (int i = 0; i < count; ++i) to[i] = uint8_t(l[first + std::size_t(i)]);
                          },
                          scalarsPerTexel(labelType_)});
    }

    std::optional<GradientPacker> packer;
    if (contents.gradients) {
        packer.emplace(prepared.scalars, table);
        gradientBase_ = packer->base();
        const Volume& scalars = prepared.scalars;
        const GradientPacker& codes = *packer;
        wholes.push_back({&gradients_, "gradients", 1, kGradientFormat,
                          [&scalars, &codes](int, std::size_t first, int count, uint8_t* to) {
                              std::uint32_t row[256];  // texels may be unaligned: packed here, then copied
                              for (int done = 0; done < count; done += 256) {
                                  const int n = std::min(256, count - done);
                                  codes.packRow(scalars, first + std::size_t(done), n, row);
                                  std::memcpy(to + 4 * std::size_t(done), row, 4 * std::size_t(n));
                              }
                          }});
    }

    const DistanceFields& f = prepared.fields;
    const bool octantFields = std::any_of(contents.casters.begin(), contents.casters.end(), usesOctants);
    std::vector<int> octantOfSlot;
    for (int oct = 0; oct < kOctants; ++oct)
        if (octantFields && (octants & (1u << oct))) {
            slot_[oct] = int(octantOfSlot.size());
            octantOfSlot.push_back(oct);
        }
    for (Caster caster : contents.casters) {
        if (caster == Caster::PC)
            wholes.push_back({&fields_[int(caster)], "pc", 1, vk::Format::eR8Uint,
                              [&f](int, std::size_t first, int count, uint8_t* to) {
                                  std::memcpy(to, f.pc.data() + first, count);
                              }});
        if (caster == Caster::ACD)
            wholes.push_back({&fields_[int(caster)], "acd", int(octantOfSlot.size()), vk::Format::eR8Uint,
                              [&f, &octantOfSlot](int slab, std::size_t first, int count, uint8_t* to) {
                                  std::memcpy(to, f.acd[octantOfSlot[slab]].data() + first, count);
                              }});
        if (caster == Caster::EACD && f.eacdCode() == ExtentCode::Exact)
            wholes.push_back({&fields_[int(caster)], "eacd", int(octantOfSlot.size()), vk::Format::eR8G8B8A8Uint,
                              [&f, &octantOfSlot](int slab, std::size_t first, int count, uint8_t* to) {
                                  const uint8_t* e = f.eacd[octantOfSlot[slab]].data() + 3 * first;
                                  for (int i = 0; i < count; ++i, to += 4, e += 3)
                                      to[0] = e[0], to[1] = e[1], to[2] = e[2], to[3] = 0;
                              }});
        else if (caster == Caster::EACD)  // the field's own bytes
            wholes.push_back({&fields_[int(caster)], "eacd", int(octantOfSlot.size()), eacdFormat(f.eacdCode()),
                              [&f, &octantOfSlot](int slab, std::size_t first, int count, uint8_t* to) {
                                  const std::size_t bytes = extentCodeBytes(f.eacdCode());
                                  std::memcpy(to, f.eacd[octantOfSlot[slab]].data() + bytes * first, bytes * count);
                              }});
    }

    // One plan for every image: the bricks of the ACD / EACD images are as many slabs deep, the hier images hold
    // as many slabs of the bricks' blocks (at most (edge + 2 B - 2) / B of them along an axis).
    int zSlabs = 1;
    for (const WholeImage& w : wholes) zSlabs = std::max(zSlabs, w.slabs);
    const bool hasHier =
        std::find(contents.casters.begin(), contents.casters.end(), Caster::Hier) != contents.casters.end();
    const int hierShift = f.hier.blockShift, hierEdge = 1 << hierShift;
    bricks_ = planBricks(dims, zSlabs, [&](const Vec3i& brick) {
        for (const WholeImage& w : wholes)
            if (!imageFits(ctx, w.extent(brick), w.format, limits)) return false;
        const Vec3i blocks{(brick.x + 2 * hierEdge - 2) >> hierShift, (brick.y + 2 * hierEdge - 2) >> hierShift,
                           (brick.z + 2 * hierEdge - 2) >> hierShift};
        return !hasHier || imageFits(ctx, {blocks.x, blocks.y, blocks.z * int(octantOfSlot.size())},
                                     vk::Format::eR16Uint, limits);
    }, limits.minBricks);
    const std::vector<Brick>& bricks = bricks_.bricks();
    for (const WholeImage& w : wholes) {
        const std::size_t texel = formatBytes(w.format);
        for (std::size_t i = 0; i < bricks.size(); ++i) {
            const Brick& b = bricks[i];
            const Vec3i extent = w.extent(b.imageDims);
            const std::size_t bytes = texel * extent.x * extent.y * extent.z;
            // The brick's box from every slab, stacked along z as the whole image stacks them; slices in parallel.
            // A row of words ends in zeros where its voxels do not fill the last word.
            auto write = [&](uint8_t* to, std::size_t rowPitch, std::size_t slicePitch) {
                tbb::parallel_for(0, extent.z, [&](int sz) {
                    const int s = sz / b.imageDims.z, z = b.imageLo.z + sz % b.imageDims.z;
                    uint8_t* slice = to + std::size_t(sz) * slicePitch;
                    for (int y = 0; y < b.imageDims.y; ++y) {
                        uint8_t* row = slice + y * rowPitch;
                        if (w.perTexel > 1) std::memset(row + (extent.x - 1) * texel, 0, texel);
                        w.row(s, linearIndex(dims, b.imageLo.x, b.imageLo.y + y, z), b.imageDims.x, row);
                    }
                });
            };
            w.bricks->push_back(
                std::make_unique<VolumeImage>(ctx, pool, extent, w.format, bytes, write, limits.staged));
            uploads_.push_back({w.name, bytes, int(i)});
        }
    }
    if (std::find(contents.casters.begin(), contents.casters.end(), Caster::Blocks) != contents.casters.end()) {
        const BlockExtrema e = vr::blockExtrema(prepared.scalars);
        const std::size_t bytes = e.range.size() * sizeof(float);
        blockExtrema_ =
            std::make_unique<VolumeImage>(ctx, pool, e.imageDims, kBlockExtremaFormat, e.range.data(), bytes);
        blockLevelZ_ = e.levelZ;
        uploads_.push_back({"blocks", bytes, 0});
    }
    if (hasHier) {
        // Per brick the blocks its images' voxels touch, each octant's slab of them stacked along z.
        const BlockEACD& h = f.hier;
        hierBlockShift_ = h.blockShift;
        for (std::size_t i = 0; i < bricks.size(); ++i) {
            const BrickBlocks blocks = brickBlocks(bricks[i].imageLo, bricks[i].imageDims, h.blockShift);
            const Vec3i texels{blocks.count.x, blocks.count.y, blocks.count.z * int(octantOfSlot.size())};
            std::vector<uint16_t> codes;
            codes.reserve(std::size_t(texels.x) * texels.y * texels.z);
            for (int oct : octantOfSlot)
                for (int z = 0; z < blocks.count.z; ++z)
                    for (int y = 0; y < blocks.count.y; ++y)
                        for (int x = 0; x < blocks.count.x; ++x)
                            codes.push_back(h.code(oct, (blocks.lo + Vec3i{x, y, z}) * (1 << h.blockShift)));
            const std::size_t bytes = codes.size() * sizeof(uint16_t);
            hier_.push_back(
                std::make_unique<VolumeImage>(ctx, pool, texels, vk::Format::eR16Uint, codes.data(), bytes));
            uploads_.push_back({"hier", bytes, int(i)});
        }
    }
    if (!scalarsFit)
        throw InputError("prepared volume: its " + std::string(scalarTypeName(scalarType_)) +
                         " scalars hold a value that is no " + std::string(scalarTypeName(scalarType_)) +
                         " (a corrupt volume)");
}

const VolumeImage* GpuVolume::field(Caster caster, int brick) const {
    if (caster == Caster::Blocks) return nullptr;
    const Bricked& f = caster == Caster::Hier ? hier_ : fields_[int(caster)];
    return f.empty() ? nullptr : f[brick].get();
}

std::size_t GpuVolume::uploadedBytes() const {
    std::size_t total = 0;
    for (const UploadedResource& u : uploads_) total += u.bytes;
    return total;
}

void GpuVolume::requireHolds(const RenderSettings& s, unsigned viewOctants) const {
    const std::string caster(casterName(s.caster));
    if (s.readsStoredGradients() && gradients_.empty())
        throw std::invalid_argument("the uploaded volume holds no stored gradients to shade by");
    if (s.caster == Caster::Blocks && !blockExtrema_)
        throw std::invalid_argument("the uploaded volume holds no block extrema for the blocks caster");
    if (leapsThroughRegions(s.caster) && !field(s.caster, 0))
        throw std::invalid_argument("the uploaded volume holds no field of the " + caster + " caster");
    if (usesOctants(s.caster))
        for (int oct = 0; oct < kOctants; ++oct)
            if ((viewOctants >> oct & 1) && slot_[oct] < 0)
                throw std::invalid_argument("the uploaded volume lacks octant " + std::to_string(oct) + " of the " +
                                            caster + " field that this view's rays need");
}

}  // namespace vr
