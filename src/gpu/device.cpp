#include "penumbra/gpu/device.hpp"

#include <vector>

#include "block_allocator.hpp"
#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {

Device::Device(const DeviceHandles& handles, const EnabledFeatures& features,
               PFN_vkGetInstanceProcAddr get_instance_proc_addr, DeviceMemoryAllocator* allocator) {
    vk_.vkGetInstanceProcAddr = get_instance_proc_addr;
    load_instance_functions(vk_, handles.instance);
    load_device_functions(vk_, handles.device);
    initialize(handles, features, 0, allocator);
}

// The own allocator's blocks are freed here, after every resource of the Device's users
// (which destroy theirs before the Device they were made on).
Device::~Device() = default;

size_t Device::own_memory_blocks() const {
    return own_allocator_ ? static_cast<const BlockAllocator&>(*own_allocator_).block_count() : 0;
}

void Device::initialize(const DeviceHandles& handles, const EnabledFeatures& features, uint32_t device_index,
                        DeviceMemoryAllocator* allocator) {
    handles_ = handles;
    sharing_families_ = {handles.queue_family, handles.compute_queue_family};
    features_ = features;
    if (allocator) {
        allocator_ = allocator;
    } else {
        own_allocator_ = std::make_unique<BlockAllocator>(*this);
        allocator_ = own_allocator_.get();
    }
    vk_.vkGetPhysicalDeviceProperties(handles.physical_device, &properties_);
    vk_.vkGetPhysicalDeviceMemoryProperties(handles.physical_device, &memory_);
    info_ = describe_physical_device(vk_, handles.physical_device, device_index);
    if (features.multiview) {
        VkPhysicalDeviceMultiviewProperties multiview{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_PROPERTIES};
        VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &multiview};
        vk_.vkGetPhysicalDeviceProperties2(handles.physical_device, &properties);
        max_multiview_views_ = multiview.maxMultiviewViewCount;
    }
}

uint32_t Device::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags wanted) const {
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
        if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
    throw VulkanError("no memory type with the requested properties", VK_ERROR_OUT_OF_DEVICE_MEMORY);
}

std::vector<VkQueueFamilyProperties> queue_families(const VulkanFunctions& vk, VkPhysicalDevice device) {
    uint32_t count = 0;
    vk.vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vk.vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    return families;
}

bool find_graphics_compute_family(const VulkanFunctions& vk, VkPhysicalDevice device, uint32_t& family) {
    const std::vector<VkQueueFamilyProperties> families = queue_families(vk, device);
    const auto count = static_cast<uint32_t>(families.size());
    constexpr VkQueueFlags kWanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & kWanted) == kWanted) {
            family = i;
            return true;
        }
    }
    return false;
}

DeviceInfo describe_physical_device(const VulkanFunctions& vk, VkPhysicalDevice device, uint32_t index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vk.vkGetPhysicalDeviceProperties2(device, &properties);
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    if (properties.properties.apiVersion >= VK_API_VERSION_1_3) vk.vkGetPhysicalDeviceFeatures2(device, &features);

    DeviceInfo info;
    info.index = index;
    info.name = properties.properties.deviceName;
    info.type = properties.properties.deviceType;
    info.driver = std::string(driver.driverName) + " (" + driver.driverInfo + ")";
    info.api_version = properties.properties.apiVersion;
    uint32_t family = 0;
    info.usable = properties.properties.apiVersion >= VK_API_VERSION_1_3 && features13.dynamicRendering &&
                  features13.synchronization2 && find_graphics_compute_family(vk, device, family);
    return info;
}

const char* device_type_name(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "cpu";
        default:
            return "other";
    }
}

std::string api_version_string(uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
           std::to_string(VK_API_VERSION_PATCH(version));
}

}  // namespace penumbra::gpu
