#include "volrender/vulkan/gpu_volume.h"

#include <cmath>
#include <cstring>

namespace vr {

GpuVolume::GpuVolume(const VulkanContext& ctx, const vk::raii::CommandPool& pool, const PreparedVolume& prepared,
                     Caster caster, bool shading, unsigned octants) {
    slot_.fill(-1);
    const ClassifiedVolume& cv = prepared.classified;
    const Vec3i dims = cv.grid.dims;
    const std::size_t voxels = cv.grid.voxels();
    auto upload = [&](const char* name, Vec3i extent, vk::Format format, const void* data, std::size_t bytes) {
        uploads_.push_back({name, bytes});
        return std::make_unique<VolumeImage>(ctx, pool, extent, format, data, bytes);
    };

    std::vector<float> rgbaSigma(voxels * 4);
    for (std::size_t i = 0; i < voxels; ++i) {
        std::memcpy(&rgbaSigma[i * 4], cv.colour[i].data(), 3 * sizeof(float));
        rgbaSigma[i * 4 + 3] = cv.sigma[i];
    }
    classified_ = upload("classified", dims, vk::Format::eR32G32B32A32Sfloat, rgbaSigma.data(),
                         rgbaSigma.size() * sizeof(float));
    rgbaSigma = {};

    if (shading) {
        // 16-bit snorm: the quantisation (1.5e-5) moves the shade by far less than the test tolerance.
        std::vector<int16_t> packed(voxels * 4, 0);
        for (std::size_t i = 0; i < voxels; ++i)
            for (int a = 0; a < 3; ++a)
                packed[i * 4 + a] = int16_t(std::lround(std::clamp(cv.normal[i][a], -1.f, 1.f) * 32767.f));
        normals_ = upload("normals", dims, vk::Format::eR16G16B16A16Snorm, packed.data(), packed.size() * 2);
    }

    const DistanceFields& f = prepared.fields;
    if (caster == Caster::PC) field_ = upload("pc", dims, vk::Format::eR8Uint, f.pc.data(), f.pc.size());
    if (caster == Caster::ACD || caster == Caster::EACD) {
        const bool eacd = caster == Caster::EACD;
        std::vector<uint8_t> slabs;
        int slots = 0;
        for (int oct = 0; oct < kOctants; ++oct) {
            if (!(octants & (1u << oct))) continue;
            slot_[oct] = slots++;
            if (eacd)
                for (const auto& e : f.eacd[oct]) slabs.insert(slabs.end(), {e[0], e[1], e[2], uint8_t(0)});
            else
                slabs.insert(slabs.end(), f.acd[oct].begin(), f.acd[oct].end());
        }
        const Vec3i extent{dims.x, dims.y, dims.z * slots};
        field_ = upload(eacd ? "eacd" : "acd", extent, eacd ? vk::Format::eR8G8B8A8Uint : vk::Format::eR8Uint,
                        slabs.data(), slabs.size());
    }
}

}  // namespace vr
