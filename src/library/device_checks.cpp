#include "library/device_checks.hpp"

#include <string>
#include <vector>

#include "penumbra/errors.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/features.hpp"

namespace penumbra::library {
namespace {

constexpr const char* kWhere = "ShadowSystem: ";

void require_handle(const void* handle, const char* name) {
    if (handle == nullptr) throw InputError(std::string(kWhere) + "DeviceDesc::" + name + " is null");
}

void require_feature(bool enabled, const char* feature) {
    if (!enabled) {
        throw DeviceError(std::string(kWhere) + "the device was created without " + feature +
                          ", which Penumbra requires (docs/library.md lists every requirement)");
    }
}

void check_queue_family(const std::vector<VkQueueFamilyProperties>& families, uint32_t family) {
    const auto count = static_cast<uint32_t>(families.size());
    if (family >= count) {
        throw InputError(std::string(kWhere) + "DeviceDesc::queue_family " + std::to_string(family) +
                         " does not exist (the device has " + std::to_string(count) + ")");
    }
    constexpr VkQueueFlags kWanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if ((families[family].queueFlags & kWanted) != kWanted) {
        throw DeviceError(std::string(kWhere) + "queue family " + std::to_string(family) +
                          " lacks VK_QUEUE_GRAPHICS_BIT and VK_QUEUE_COMPUTE_BIT, which Penumbra's passes need");
    }
}

// The async compute family, when the caller names one: it exists, computes, and is not the
// graphics queue's own (whose queue needs no sharing: record_visibility() runs there).
void check_compute_queue_family(const std::vector<VkQueueFamilyProperties>& families, const DeviceDesc& desc) {
    if (desc.compute_queue_family == VK_QUEUE_FAMILY_IGNORED) return;
    const std::string field =
        std::string(kWhere) + "DeviceDesc::compute_queue_family " + std::to_string(desc.compute_queue_family);
    if (desc.compute_queue_family >= families.size()) {
        throw InputError(field + " does not exist (the device has " + std::to_string(families.size()) + ")");
    }
    if (desc.compute_queue_family == desc.queue_family) {
        throw InputError(field +
                         " is queue_family itself: leave it VK_QUEUE_FAMILY_IGNORED and record the resolve on that "
                         "queue with record_visibility()");
    }
    if ((families[desc.compute_queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT) == 0) {
        throw InputError(field + " lacks VK_QUEUE_COMPUTE_BIT");
    }
    require_handle(desc.compute_queue, "compute_queue");
}

}  // namespace

gpu::EnabledFeatures check_device(const DeviceDesc& desc, PFN_vkGetInstanceProcAddr get_instance_proc_addr) {
    require_handle(desc.instance, "instance");
    require_handle(desc.physical_device, "physical_device");
    require_handle(desc.device, "device");
    require_handle(desc.queue, "queue");
    if (desc.enabled_features == nullptr) {
        throw InputError(std::string(kWhere) +
                         "DeviceDesc::enabled_features is null: pass the VkPhysicalDeviceFeatures2 chain the device "
                         "was created with");
    }
    if (desc.instance_api_version < VK_API_VERSION_1_3) {
        throw DeviceError(std::string(kWhere) + "the instance was created for Vulkan " +
                          gpu::api_version_string(desc.instance_api_version) +
                          " (DeviceDesc::instance_api_version); Penumbra needs 1.3");
    }
    gpu::VulkanFunctions vk;
    vk.vkGetInstanceProcAddr = get_instance_proc_addr;
    gpu::load_instance_functions(vk, desc.instance);
    VkPhysicalDeviceProperties properties{};
    vk.vkGetPhysicalDeviceProperties(desc.physical_device, &properties);
    if (properties.apiVersion < VK_API_VERSION_1_3) {
        throw DeviceError(std::string(kWhere) + "device " + properties.deviceName + " supports Vulkan " +
                          gpu::api_version_string(properties.apiVersion) + "; Penumbra needs 1.3");
    }
    const std::vector<VkQueueFamilyProperties> families = gpu::queue_families(vk, desc.physical_device);
    check_queue_family(families, desc.queue_family);
    check_compute_queue_family(families, desc);

    const gpu::FeatureChain chain = gpu::read_feature_chain(*desc.enabled_features);
    require_feature(chain.dynamic_rendering, "VkPhysicalDeviceVulkan13Features::dynamicRendering");
    require_feature(chain.synchronization2, "VkPhysicalDeviceVulkan13Features::synchronization2");
    return {chain.multiview, chain.depth_clamp, chain.depth_bias_clamp, chain.gpu_driven(), chain.virtual_pages()};
}

}  // namespace penumbra::library
