#include "volrender/vulkan/vulkan_context.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace vr {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string typeName(vk::PhysicalDeviceType type) {
    switch (type) {
        case vk::PhysicalDeviceType::eDiscreteGpu: return "discrete";
        case vk::PhysicalDeviceType::eIntegratedGpu: return "integrated";
        case vk::PhysicalDeviceType::eVirtualGpu: return "virtual";
        case vk::PhysicalDeviceType::eCpu: return "cpu";
        default: return "other";
    }
}

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

bool layerInstalled(const vk::raii::Context& context, const char* name) {
    for (const auto& layer : context.enumerateInstanceLayerProperties())
        if (std::strcmp(layer.layerName, name) == 0) return true;
    return false;
}

bool extensionInstalled(const vk::raii::Context& context, const char* name) {
    for (const auto& ext : context.enumerateInstanceExtensionProperties())
        if (std::strcmp(ext.extensionName, name) == 0) return true;
    return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data,
                                         void* user) {
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)
        static_cast<VulkanContext*>(user)->recordValidationError(data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

int computeQueueFamily(const vk::raii::PhysicalDevice& device) {
    auto families = device.getQueueFamilyProperties();
    for (uint32_t i = 0; i < families.size(); ++i)
        if (families[i].queueFlags & vk::QueueFlagBits::eCompute) return int(i);
    return -1;
}

vk::raii::Instance makeInstance(const vk::raii::Context& context, bool validation) {
    vk::ApplicationInfo app("volrender", 1, "volrender", 1, VK_API_VERSION_1_1);
    std::vector<const char*> layers, extensions;
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    return vk::raii::Instance(context, vk::InstanceCreateInfo({}, &app, layers, extensions));
}

// The index of the device `requested` (-1: the first discrete GPU with a compute queue, else the first device with
// one). Throws when there is none or it has no compute queue.
int chooseDevice(const vk::raii::PhysicalDevices& devices, int requested) {
    if (devices.empty()) throw std::runtime_error("no Vulkan device found");
    int chosen = requested;
    if (chosen >= int(devices.size()))
        throw std::runtime_error("Vulkan device " + std::to_string(chosen) + " does not exist (" +
                                 std::to_string(devices.size()) + " found; see --list-devices)");
    if (chosen < 0) {
        for (std::size_t i = 0; i < devices.size() && chosen < 0; ++i)
            if (devices[i].getProperties().deviceType == vk::PhysicalDeviceType::eDiscreteGpu &&
                computeQueueFamily(devices[i]) >= 0)
                chosen = int(i);
        for (std::size_t i = 0; i < devices.size() && chosen < 0; ++i)
            if (computeQueueFamily(devices[i]) >= 0) chosen = int(i);
    }
    if (chosen < 0 || computeQueueFamily(devices[chosen]) < 0)
        throw std::runtime_error("no Vulkan device with a compute queue");
    return chosen;
}

VulkanDeviceInfo deviceInfo(const vk::raii::PhysicalDevice& device, int index) {
    const auto props = device.getProperties();
    return {index, props.deviceName.data(), typeName(props.deviceType), versionString(props.apiVersion)};
}

}  // namespace

VulkanContext::VulkanContext(const VulkanOptions& options) {
    const char* env = std::getenv("VR_VALIDATION");
    bool wanted = options.validation || (env && std::string(env) == "1");
    validation_ = wanted && layerInstalled(context_, kValidationLayer) &&
                  extensionInstalled(context_, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    instance_ = makeInstance(context_, validation_);
    if (validation_) {
        using S = vk::DebugUtilsMessageSeverityFlagBitsEXT;
        using T = vk::DebugUtilsMessageTypeFlagBitsEXT;
        messenger_ = vk::raii::DebugUtilsMessengerEXT(
            instance_, vk::DebugUtilsMessengerCreateInfoEXT({}, S::eError,
                                                            T::eGeneral | T::eValidation | T::ePerformance,
                                                            &onMessage, this));
    }

    vk::raii::PhysicalDevices devices(instance_);
    const int chosen = chooseDevice(devices, options.deviceIndex);
    physical_ = std::move(devices[chosen]);
    info_ = deviceInfo(physical_, chosen);
    if (physical_.getProperties().apiVersion < VK_API_VERSION_1_1)
        throw std::runtime_error(info_.name + " supports only Vulkan " + info_.apiVersion + " (1.1 needed)");

    queueFamily_ = uint32_t(computeQueueFamily(physical_));
    float priority = 1.0f;
    vk::DeviceQueueCreateInfo queueInfo({}, queueFamily_, 1, &priority);
    // The casters compute in float and 32-bit integers (docs/ALGORITHMS.md section 8), so the device enables
    // neither shaderFloat64 nor shaderInt64. They read every volume as a storage image
    // (volrender/vulkan/gpu_buffer.h), whose formats for the integer scalars and the fields are extended storage
    // formats; VulkanRenderer checks each format's storage-image support (requireCasterImageSupport).
    if (!physical_.getFeatures().shaderStorageImageExtendedFormats)
        throw std::runtime_error(info_.name + " lacks shaderStorageImageExtendedFormats, which the casters need");
    vk::PhysicalDeviceFeatures features;
    features.shaderStorageImageExtendedFormats = VK_TRUE;
    device_ = vk::raii::Device(physical_, vk::DeviceCreateInfo({}, queueInfo, {}, {}, &features));
    queue_ = vk::raii::Queue(device_, queueFamily_, 0);
}

std::vector<VulkanDeviceInfo> VulkanContext::listDevices() {
    vk::raii::Context context;
    vk::raii::Instance instance = makeInstance(context, false);
    std::vector<VulkanDeviceInfo> out;
    vk::raii::PhysicalDevices devices(instance);
    for (std::size_t i = 0; i < devices.size(); ++i) out.push_back(deviceInfo(devices[i], int(i)));
    return out;
}

std::vector<std::string> VulkanContext::validationErrors() const {
    std::lock_guard lock(errorsMutex_);
    return errors_;
}

void VulkanContext::recordValidationError(std::string message) {
    std::lock_guard lock(errorsMutex_);
    errors_.push_back(std::move(message));
}

uint32_t VulkanContext::memoryType(uint32_t typeBits, vk::MemoryPropertyFlags required,
                                   vk::MemoryPropertyFlags preferred) const {
    auto memory = physical_.getMemoryProperties();
    int fallback = -1;
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        auto flags = memory.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback < 0) fallback = int(i);
    }
    if (fallback < 0) throw std::runtime_error("no suitable Vulkan memory type on " + info_.name);
    return uint32_t(fallback);
}

}  // namespace vr
