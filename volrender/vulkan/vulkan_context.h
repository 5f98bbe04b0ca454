// The Vulkan instance, the chosen physical device, one compute queue and the validation messenger.
#pragma once
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

namespace vr {

struct VulkanDeviceInfo {
    int index = 0;
    std::string name;
    std::string type;  // "discrete", "integrated", "virtual", "cpu", "other"
    std::string apiVersion;
};

struct VulkanOptions {
    int deviceIndex = -1;  // -1: the first discrete GPU, else the first device with a compute queue
    // Enables VK_LAYER_KHRONOS_validation when installed; when false, the env VR_VALIDATION=1 still enables it.
    bool validation = false;
};

class VulkanContext {
public:
    explicit VulkanContext(const VulkanOptions& options = {});
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    static std::vector<VulkanDeviceInfo> listDevices();

    const vk::raii::PhysicalDevice& physicalDevice() const { return physical_; }
    const vk::raii::Device& device() const { return device_; }
    const vk::raii::Queue& queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const VulkanDeviceInfo& info() const { return info_; }
    bool validationEnabled() const { return validation_; }

    // Messages of severity error reported by the validation layer since creation (tests assert none).
    std::vector<std::string> validationErrors() const;
    void recordValidationError(std::string message);

    // Index of a memory type with all of `required` among `typeBits`, preferring one that also has `preferred`.
    uint32_t memoryType(uint32_t typeBits, vk::MemoryPropertyFlags required,
                        vk::MemoryPropertyFlags preferred = {}) const;

private:
    vk::raii::Context context_;
    vk::raii::Instance instance_{nullptr};
    vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
    vk::raii::PhysicalDevice physical_{nullptr};
    vk::raii::Device device_{nullptr};
    vk::raii::Queue queue_{nullptr};
    uint32_t queueFamily_ = 0;
    VulkanDeviceInfo info_;
    bool validation_ = false;
    mutable std::mutex errorsMutex_;
    std::vector<std::string> errors_;
};

}  // namespace vr
