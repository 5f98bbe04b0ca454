#include "volrender/vulkan/gpu_volume.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "render/render_checks.h"

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
};

// A normal component as RGBA16_SNORM holds it: std::lround(clamp(x, -1, 1) * 32767) without the library call (a
// float of magnitude <= 32767 plus 0.5 is exact in double, and the conversion truncates toward zero).
int16_t snorm16(float x) {
    const double v = std::clamp(x, -1.f, 1.f) * 32767.f;
    return int16_t(v + (v < 0 ? -0.5 : 0.5));
}

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

GpuVolume::GpuVolume(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const PreparedVolume& prepared,
                     const GpuVolumeContents& contents, const ImageLimits& limits)
    : grid_(prepared.classified.grid), contents_(contents), eacdCode_(prepared.fields.eacdCode()) {
    slot_.fill(-1);
    const bool shading = contents.shading;
    const unsigned octants = contents.octants;
    for (Caster caster : contents.casters) {
        RenderSettings needs;
        needs.caster = caster;
        needs.shading = shading;
        checkRenderInputs(prepared, needs);
        if ((caster == Caster::ACD || caster == Caster::EACD) && (octants & 0xffu) == 0)
            throw std::invalid_argument("uploading the " + std::string(casterName(caster)) + " field needs octants");
    }
    segmentedForTrilinear_ = prepared.meta.segmentation.trilinear;
    const ClassifiedVolume& cv = prepared.classified;
    const Vec3i dims = cv.grid.dims;
    std::vector<WholeImage> wholes;

    wholes.push_back({&classified_, "classified", 1, vk::Format::eR32G32B32A32Sfloat,
                      [&cv](int, std::size_t first, int count, uint8_t* to) {
                          for (std::size_t i = first; i < first + count; ++i, to += 16) {
                              std::memcpy(to, cv.colour[i].data(), 3 * sizeof(float));
                              std::memcpy(to + 12, &cv.sigma[i], sizeof(float));
                          }
                      }});
    if (shading) {
        // 16-bit snorm: the quantisation (1.5e-5) moves the shade by far less than the test tolerance.
        wholes.push_back({&normals_, "normals", 1, vk::Format::eR16G16B16A16Snorm,
                          [&cv](int, std::size_t first, int count, uint8_t* to) {
                              for (std::size_t i = first; i < first + count; ++i, to += 8) {
                                  int16_t packed[4] = {0, 0, 0, 0};
                                  for (int a = 0; a < 3; ++a) packed[a] = snorm16(cv.normal[i][a]);
                                  std::memcpy(to, packed, sizeof(packed));
                              }
                          }});
    }

    const DistanceFields& f = prepared.fields;
    const bool octantFields = std::any_of(contents.casters.begin(), contents.casters.end(),
                                          [](Caster c) { return c == Caster::ACD || c == Caster::EACD; });
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

    // One plan for every image: the bricks of the ACD / EACD images are as many slabs deep.
    int zSlabs = 1;
    for (const WholeImage& w : wholes) zSlabs = std::max(zSlabs, w.slabs);
    bricks_ = planBricks(dims, zSlabs, [&](const Vec3i& brick) {
        for (const WholeImage& w : wholes)
            if (!imageFits(ctx, {brick.x, brick.y, brick.z * w.slabs}, w.format, limits)) return false;
        return true;
    });
    const std::vector<Brick>& bricks = bricks_.bricks();
    for (const WholeImage& w : wholes) {
        const std::size_t texel = formatBytes(w.format);
        for (std::size_t i = 0; i < bricks.size(); ++i) {
            const Brick& b = bricks[i];
            const Vec3i extent{b.imageDims.x, b.imageDims.y, b.imageDims.z * w.slabs};
            const std::size_t bytes = texel * b.imageDims.x * b.imageDims.y * extent.z;
            // The brick's box from every slab, stacked along z as the whole image stacks them; slices in parallel.
            auto write = [&](uint8_t* to, std::size_t rowPitch, std::size_t slicePitch) {
                tbb::parallel_for(0, extent.z, [&](int sz) {
                    const int s = sz / b.imageDims.z, z = b.imageLo.z + sz % b.imageDims.z;
                    uint8_t* slice = to + std::size_t(sz) * slicePitch;
                    for (int y = 0; y < b.imageDims.y; ++y)
                        w.row(s, linearIndex(dims, b.imageLo.x, b.imageLo.y + y, z), b.imageDims.x,
                              slice + y * rowPitch);
                });
            };
            w.bricks->push_back(std::make_unique<VolumeImage>(ctx, pool, extent, w.format, bytes, write, limits.staged));
            uploads_.push_back({w.name, bytes, int(i)});
        }
    }
}

const VolumeImage* GpuVolume::field(Caster caster, int brick) const {
    const Bricked& f = fields_[int(caster)];
    return f.empty() ? nullptr : f[brick].get();
}

std::size_t GpuVolume::uploadedBytes() const {
    std::size_t total = 0;
    for (const UploadedResource& u : uploads_) total += u.bytes;
    return total;
}

void GpuVolume::requireHolds(const RenderSettings& s, unsigned viewOctants) const {
    const std::string caster(casterName(s.caster));
    if (s.caster != Caster::Primitive && fields_[int(s.caster)].empty())
        throw std::invalid_argument("the uploaded volume holds no field of the " + caster + " caster");
    if (s.shading && normals_.empty())
        throw std::invalid_argument("the uploaded volume holds no normals: shading needs them");
    if (s.caster == Caster::ACD || s.caster == Caster::EACD)
        for (int oct = 0; oct < kOctants; ++oct)
            if ((viewOctants >> oct & 1) && slot_[oct] < 0)
                throw std::invalid_argument("the uploaded volume lacks octant " + std::to_string(oct) + " of the " +
                                            caster + " field that this view's rays need");
}

}  // namespace vr
