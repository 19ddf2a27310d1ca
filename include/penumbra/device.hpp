#pragma once
// The Vulkan device a ShadowSystem works on: the caller's own (DeviceDesc), or one that
// VulkanContext creates for callers without a renderer of their own.
//
// What the caller's device must have (docs/library.md, "Device requirements"):
//   - an instance created with VkApplicationInfo::apiVersion >= VK_API_VERSION_1_3 on a
//     physical device of Vulkan 1.3 or later;
//   - VkPhysicalDeviceVulkan13Features::dynamicRendering and ::synchronization2 enabled;
//   - the queue Penumbra's commands are submitted on from a family with both
//     VK_QUEUE_GRAPHICS_BIT and VK_QUEUE_COMPUTE_BIT.
// Used when enabled, never required: VkPhysicalDeviceFeatures::depthClamp (casters in
// front of a shadow map's near plane are flattened onto it) and ::depthBiasClamp (the
// slope bias is clamped), VkPhysicalDeviceVulkan11Features::multiview (only the
// ShadowStrategy::Multiview setting needs it). No device or instance extension is needed.
#include <vulkan/vulkan_core.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "penumbra/memory.hpp"

namespace penumbra {

// The caller's device. Penumbra never creates, submits to or destroys any of these.
struct DeviceDesc {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    // The queue the caller submits Penumbra's recorded commands on, and its family
    // (Penumbra reads the family's capabilities and timestamp support).
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    // VkApplicationInfo::apiVersion the instance was created with (Vulkan cannot be asked).
    uint32_t instance_api_version = 0;
    // The VkPhysicalDeviceFeatures2 chain the device was created with (VkDeviceCreateInfo::
    // pNext), which Penumbra reads to know what is enabled: VkPhysicalDeviceVulkan11Features,
    // VkPhysicalDeviceVulkan13Features (or VkPhysicalDeviceDynamicRenderingFeatures and
    // VkPhysicalDeviceSynchronization2Features) and VkPhysicalDeviceMultiviewFeatures are
    // understood. Only read during the ShadowSystem's construction.
    const VkPhysicalDeviceFeatures2* enabled_features = nullptr;
    // The loader entry point the caller uses (e.g. volk's or its own); nullptr = the Vulkan
    // loader that Penumbra links. Every Vulkan function Penumbra calls comes through it.
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    // Where the ShadowSystem's images and buffers get their device memory (penumbra/memory.hpp):
    // the caller's allocator, which must outlive the ShadowSystem; nullptr = Penumbra's own,
    // which sub-allocates from blocks of 64 MiB.
    DeviceMemoryAllocator* allocator = nullptr;
    // Async compute (ShadowSystem::record_visibility_async()): a queue family with
    // VK_QUEUE_COMPUTE_BIT other than queue_family, and the queue of it the caller submits
    // the resolve on (~ShadowSystem waits for it as for `queue`). Penumbra's images and
    // buffers are then shared by both families (VK_SHARING_MODE_CONCURRENT) and never change
    // hands; the caller's screen images and visibility target do (docs/library.md, "Async
    // compute"). VK_QUEUE_FAMILY_IGNORED: none, everything on `queue`.
    uint32_t compute_queue_family = VK_QUEUE_FAMILY_IGNORED;
    VkQueue compute_queue = VK_NULL_HANDLE;
};

// What a physical device offers, for choosing one.
struct PhysicalDeviceInfo {
    uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order
    std::string name;
    std::string type;    // "discrete", "integrated", "virtual", "cpu" or "other"
    std::string driver;  // driver name and version, e.g. "llvmpipe (Mesa 22.3.6)"
    uint32_t api_version = 0;
    bool usable = false;  // meets the requirements above
};

// The physical devices of a fresh instance. Throws DeviceError without a Vulkan driver.
std::vector<PhysicalDeviceInfo> list_physical_devices();

// "1.3.255"
std::string vulkan_version_string(uint32_t version);

// Warnings and errors of the validation layer, in the order they were reported. Shared, so
// that what the layer reports while the device and instance are destroyed (leaks) can
// still be read once the VulkanContext is gone.
struct ValidationLog {
    std::vector<std::string> messages;
};

struct VulkanContextOptions {
    // The Khronos validation layer with synchronization validation. Its warnings and
    // errors go to `validation_log` and to `on_validation_message`, if set.
    bool validation = false;
    std::shared_ptr<ValidationLog> validation_log = std::make_shared<ValidationLog>();
    std::function<void(const std::string& message)> on_validation_message;
    // With validation: the layer's best-practices checks as well (valid but wasteful use:
    // small allocations, redundant barriers, ...), reported the same way.
    bool best_practices = false;
    // "" = the best usable device (discrete, integrated, virtual, then CPU); otherwise an
    // index from list_physical_devices() or a case-insensitive part of a device name.
    std::string device_selector;
    // For a window: extra instance extensions (e.g. glfwGetRequiredInstanceExtensions);
    // the device then also gets VK_KHR_swapchain.
    std::vector<std::string> presentation_extensions;
    // A second queue for async compute, from a family with compute and without graphics
    // (the queues GPUs run beside graphics work), when the device has one: DeviceDesc's
    // compute_queue_family and compute_queue name it; otherwise they stay unset.
    bool async_compute = false;
    // For a window: whether (instance, physical device, queue family) can present to it.
    std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)> can_present;
};

// A Vulkan 1.3 instance and device created with exactly the features Penumbra uses (the
// required ones, and every optional one the device supports), and one graphics + compute
// queue. For callers without a renderer of their own: the `penumbra` tools use it.
class VulkanContext {
public:
    // Throws DeviceError when there is no usable device, the selector matches none, or
    // validation is asked for and the layer is missing.
    explicit VulkanContext(const VulkanContextOptions& options = {});
    ~VulkanContext();  // waits for the device to be idle, then destroys device and instance
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    // The description to create a ShadowSystem with.
    const DeviceDesc& device_desc() const;
    const PhysicalDeviceInfo& physical_device_info() const;
    // Whether the validation layer is on (VulkanContextOptions::validation).
    bool validation_enabled() const;

    struct State;  // the device layer's context; opaque to callers

private:
    std::unique_ptr<State> state_;
};

}  // namespace penumbra
