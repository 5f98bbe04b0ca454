// shaders/numerics.glsl (expm1 written in GLSL float) against the C library's double, evaluated on the device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "shaders/embedded_shaders.h"
#include "support/vulkan.h"
#include "volrender/vulkan/gpu_buffer.h"
#include "volrender/vulkan/vulkan_renderer.h"

namespace vr {
namespace {

// Runs numerics_test.comp over `x`: expm1 of each.
std::vector<float> expm1OnDevice(const VulkanContext& ctx, const std::vector<float>& x) {
    const vk::raii::Device& device = ctx.device();
    const vk::DeviceSize bytes = x.size() * sizeof(float);
    const auto usage = vk::BufferUsageFlagBits::eStorageBuffer;
    HostBuffer in(ctx, bytes, usage), out(ctx, bytes, usage);
    std::memcpy(in.data(), x.data(), bytes);

    const auto compute = vk::ShaderStageFlagBits::eCompute;
    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    for (uint32_t b = 0; b < 2; ++b) bindings.emplace_back(b, vk::DescriptorType::eStorageBuffer, 1, compute);
    vk::raii::DescriptorSetLayout setLayout(device, vk::DescriptorSetLayoutCreateInfo({}, bindings));
    vk::PushConstantRange push(compute, 0, sizeof(uint32_t));
    vk::DescriptorSetLayout layoutHandle = *setLayout;
    vk::raii::PipelineLayout layout(device, vk::PipelineLayoutCreateInfo({}, layoutHandle, push));
    vk::raii::ShaderModule shader(device, vk::ShaderModuleCreateInfo({}, numerics_test_spv));
    vk::raii::Pipeline pipeline(device, nullptr,
                                vk::ComputePipelineCreateInfo({}, {{}, compute, *shader, "main"}, *layout));
    vk::DescriptorPoolSize size(vk::DescriptorType::eStorageBuffer, 2);
    vk::raii::DescriptorPool pool(
        device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, size));
    vk::raii::DescriptorSets sets(device, vk::DescriptorSetAllocateInfo(*pool, layoutHandle));
    const vk::DescriptorBufferInfo infos[2] = {{*in.buffer(), 0, VK_WHOLE_SIZE}, {*out.buffer(), 0, VK_WHOLE_SIZE}};
    std::vector<vk::WriteDescriptorSet> writes;
    for (uint32_t b = 0; b < 2; ++b)
        writes.emplace_back(*sets[0], b, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &infos[b]);
    device.updateDescriptorSets(writes, {});

    vk::raii::CommandPool commandPool(device, vk::CommandPoolCreateInfo({}, ctx.queueFamily()));
    const uint32_t count = uint32_t(x.size());
    submitAndWait(ctx, commandPool, [&](const vk::raii::CommandBuffer& cmd) {
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline);
        cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout, 0, *sets[0], {});
        cmd.pushConstants<uint32_t>(*layout, compute, 0, count);
        cmd.dispatch((count + 63) / 64, 1, 1);
        vk::MemoryBarrier toHost(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
        cmd.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, toHost,
                            {}, {});
    });
    std::vector<float> expm1(x.size());
    std::memcpy(expm1.data(), out.data(), bytes);
    return expm1;
}

double relativeError(double got, double want) {
    if (std::isinf(want)) return got == want ? 0 : 1;
    return std::abs(got - want) / std::abs(want);
}

// The requirement is a relative error below 1e-5; the float series reach a few float roundings (2^-24 each),
// checked at 1e-6 against the double expm1 of the same float argument. Beyond 88.7 the float result overflows.
TEST(VulkanNumerics, Expm1MatchesTheCLibraryFrom1eMinus12To1e3) {
    const VulkanContext& ctx = test::vulkanContext();
    // |x| from 1e-12 to 1e3, 200 points per decade, both signs, and the branch ends.
    std::vector<float> x;
    for (int i = 0; i <= 15 * 200; ++i) {
        const float m = float(std::pow(10.0, -12 + i / 200.0));
        x.push_back(m);
        x.push_back(-m);
    }
    for (float special : {0.5f, -0.5f, 1.0f, -0.4999f, 0.9999f, 1e-3f, -1e-3f, 88.0f, -87.0f, 1e-30f, -1e-30f})
        x.push_back(special);
    const std::vector<float> got = expm1OnDevice(ctx, x);

    double worst = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double want = std::expm1(double(x[i]));
        const double err = x[i] > 88.7f ? (std::isinf(got[i]) ? 0 : 1) : relativeError(got[i], want);
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-6) << "expm1(" << x[i] << ") = " << got[i] << ", want " << want;
    }
    std::printf("worst relative error of expm1: %.3g\n", worst);
    test::expectNoValidationErrors();
}

TEST(VulkanNumerics, SpanOpacityOfTinyExtinctionKeepsItsValue) {
    // The stiff case of docs/ALGORITHMS.md section 6: 1 - (1 - 1e-8)^10000 in float is 0; expm1 keeps ~1e-4.
    const VulkanContext& ctx = test::vulkanContext();
    const float sigmaL = float(-std::log1p(-1e-8) * 10000);
    const std::vector<float> got = expm1OnDevice(ctx, {-sigmaL});
    EXPECT_NEAR(-got[0], -std::expm1(-double(sigmaL)), 1e-6 * std::expm1(double(sigmaL)));
    EXPECT_EQ(1.0f - std::pow(1.0f - 1e-8f, 10000.0f), 0.0f);  // what the naive float formula gives
}

}  // namespace
}  // namespace vr
