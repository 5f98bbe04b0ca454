// The validation layer's messenger, which every Vulkan test relies on when it checks that the layer reported no
// error (tests/support/vulkan.h: expectNoValidationErrors).
#include <gtest/gtest.h>

#include "volrender/vulkan/vulkan_context.h"

namespace vr {
namespace {

// The messenger the other tests rely on ("no validation errors") does record errors: a zero-sized buffer is one.
TEST(VulkanValidation, MessengerRecordsErrors) {
    VulkanContext ctx(VulkanOptions{-1, true});
    ASSERT_TRUE(ctx.validationEnabled()) << "VK_LAYER_KHRONOS_validation is not installed";
    EXPECT_TRUE(ctx.validationErrors().empty());
    try {
        vk::raii::Buffer buffer(ctx.device(), vk::BufferCreateInfo({}, 0, vk::BufferUsageFlagBits::eStorageBuffer));
    } catch (const vk::SystemError&) {
        // The driver may refuse it too; the layer has spoken first.
    }
    EXPECT_FALSE(ctx.validationErrors().empty());
}

}  // namespace
}  // namespace vr
