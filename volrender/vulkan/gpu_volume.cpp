#include "volrender/vulkan/gpu_volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "volrender/render_checks.h"

namespace vr {
namespace {

// One image of the whole volume, waiting for the brick plan that every image of the volume fits.
struct WholeImage {
    std::vector<std::unique_ptr<VolumeImage>>* bricks;
    const char* name;
    Vec3i extent;  // z: slabs x the volume's z
    vk::Format format;
    std::vector<uint8_t> texels;
};

// The texels of one brick's box from every z-slab of a whole image, stacked along z as the whole image stacks them.
std::vector<uint8_t> cropBrick(const WholeImage& whole, const Vec3i& dims, const Brick& b) {
    const int slabs = whole.extent.z / dims.z;
    const std::size_t texel = whole.texels.size() / (std::size_t(whole.extent.x) * whole.extent.y * whole.extent.z);
    const std::size_t row = std::size_t(b.imageDims.x) * texel;
    std::vector<uint8_t> out(row * b.imageDims.y * b.imageDims.z * slabs);
    uint8_t* to = out.data();
    for (int s = 0; s < slabs; ++s)
        for (int z = 0; z < b.imageDims.z; ++z)
            for (int y = 0; y < b.imageDims.y; ++y, to += row) {
                const std::size_t from =
                    linearIndex(whole.extent, b.imageLo.x, b.imageLo.y + y, s * dims.z + b.imageLo.z + z);
                std::memcpy(to, whole.texels.data() + from * texel, row);
            }
    return out;
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
    : grid_(prepared.classified.grid), contents_(contents), eacdCode_(prepared.fields.eacdCode) {
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
    const std::size_t voxels = cv.grid.voxels();
    std::vector<WholeImage> wholes;
    auto upload = [&](Bricked& bricks, const char* name, Vec3i extent, vk::Format format, const void* data,
                      std::size_t bytes) {
        const auto* begin = static_cast<const uint8_t*>(data);
        wholes.push_back({&bricks, name, extent, format, std::vector<uint8_t>(begin, begin + bytes)});
    };

    std::vector<float> rgbaSigma(voxels * 4);
    for (std::size_t i = 0; i < voxels; ++i) {
        std::memcpy(&rgbaSigma[i * 4], cv.colour[i].data(), 3 * sizeof(float));
        rgbaSigma[i * 4 + 3] = cv.sigma[i];
    }
    upload(classified_, "classified", dims, vk::Format::eR32G32B32A32Sfloat, rgbaSigma.data(),
           rgbaSigma.size() * sizeof(float));
    rgbaSigma = {};

    if (shading) {
        // 16-bit snorm: the quantisation (1.5e-5) moves the shade by far less than the test tolerance.
        std::vector<int16_t> packed(voxels * 4, 0);
        for (std::size_t i = 0; i < voxels; ++i)
            for (int a = 0; a < 3; ++a)
                packed[i * 4 + a] = int16_t(std::lround(std::clamp(cv.normal[i][a], -1.f, 1.f) * 32767.f));
        upload(normals_, "normals", dims, vk::Format::eR16G16B16A16Snorm, packed.data(), packed.size() * 2);
    }

    const DistanceFields& f = prepared.fields;
    for (Caster caster : contents.casters) {
        if (caster == Caster::PC)
            upload(fields_[int(caster)], "pc", dims, vk::Format::eR8Uint, f.pc.data(), f.pc.size());
        if (caster == Caster::ACD || caster == Caster::EACD) {
            const bool eacd = caster == Caster::EACD;
            std::vector<uint8_t> slabs;
            int slots = 0;
            for (int oct = 0; oct < kOctants; ++oct) {
                if (!(octants & (1u << oct))) continue;
                slot_[oct] = slots++;
                if (eacd && f.eacdCode == ExtentCode::Exact)
                    for (const auto& e : f.eacd[oct]) slabs.insert(slabs.end(), {e[0], e[1], e[2], uint8_t(0)});
                else if (eacd) {
                    const std::vector<uint8_t> coded = encodeExtentField(f.eacdCode, f.eacd[oct]);
                    slabs.insert(slabs.end(), coded.begin(), coded.end());
                } else
                    slabs.insert(slabs.end(), f.acd[oct].begin(), f.acd[oct].end());
            }
            const Vec3i extent{dims.x, dims.y, dims.z * slots};
            upload(fields_[int(caster)], eacd ? "eacd" : "acd", extent,
                   eacd ? eacdFormat(f.eacdCode) : vk::Format::eR8Uint, slabs.data(), slabs.size());
        }
    }

    // One plan for every image: the bricks of the ACD / EACD images are as many slabs deep.
    int zSlabs = 1;
    for (const WholeImage& w : wholes) zSlabs = std::max(zSlabs, w.extent.z / dims.z);
    bricks_ = planBricks(dims, zSlabs, [&](const Vec3i& brick) {
        for (const WholeImage& w : wholes)
            if (!imageFits(ctx, {brick.x, brick.y, brick.z * (w.extent.z / dims.z)}, w.format, limits)) return false;
        return true;
    });
    const std::vector<Brick>& bricks = bricks_.bricks();
    for (WholeImage& w : wholes) {
        const int slabs = w.extent.z / dims.z;
        for (std::size_t i = 0; i < bricks.size(); ++i) {
            const Brick& b = bricks[i];
            const Vec3i extent{b.imageDims.x, b.imageDims.y, b.imageDims.z * slabs};
            const std::vector<uint8_t> texels = bricks.size() == 1 ? std::vector<uint8_t>() : cropBrick(w, dims, b);
            const std::vector<uint8_t>& from = bricks.size() == 1 ? w.texels : texels;
            w.bricks->push_back(std::make_unique<VolumeImage>(ctx, pool, extent, w.format, from.data(), from.size()));
            uploads_.push_back({w.name, from.size(), int(i)});
        }
        w.texels = {};
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
