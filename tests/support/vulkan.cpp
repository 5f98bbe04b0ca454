#include "support/vulkan.h"

#include <gtest/gtest.h>

#include <memory>

namespace vr::test {

VulkanContext& vulkanContext() {
    static VulkanContext ctx(VulkanOptions{-1, true});
    return ctx;
}

VulkanRenderer& vulkanRenderer(int tileSize) {
    VulkanContext& ctx = vulkanContext();  // made first, so that it outlives the renderers
    static std::map<int, std::unique_ptr<VulkanRenderer>> renderers;
    std::unique_ptr<VulkanRenderer>& r = renderers[tileSize];
    if (!r) {
        r = std::make_unique<VulkanRenderer>(ctx, tileSize);
        r->setRecastPieces(1);  // whole rays on every device: re-casts equal the full render's pixels
    }
    return *r;
}

RenderFn vulkanRender(int tileSize) {
    return [tileSize](const PreparedVolume& p, const Camera& c, const RenderSettings& s) {
        return vulkanRenderer(tileSize).render(p, c, s);
    };
}

void expectNoValidationErrors() {
    EXPECT_TRUE(vulkanContext().validationEnabled()) << "VK_LAYER_KHRONOS_validation is not installed";
    const std::vector<std::string> errors = vulkanContext().validationErrors();
    EXPECT_TRUE(errors.empty()) << errors.size() << " validation errors, first: " << errors.front();
}

void reportValidated(const char* family, const CaseCount& n) {
    report(family, n);
    expectNoValidationErrors();
}

std::map<std::string, std::size_t> bytesByName(const std::vector<UploadedResource>& uploads) {
    std::map<std::string, std::size_t> out;
    for (const UploadedResource& u : uploads) out[u.name] += u.bytes;
    return out;
}

}  // namespace vr::test
