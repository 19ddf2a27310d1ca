#pragma once
// The device layer's view of a Vulkan device: handles, the function table they are used
// through, and what the device can do. A Device owns nothing: the caller (or the library's
// VulkanContext, which creates one) keeps the instance and device alive and destroys them.
//
// Calls go through the table: `device->vkCmdDraw(cmd, ...)` (operator-> reaches the
// VulkanFunctions of this device; see gpu/dispatch.hpp).
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "penumbra/gpu/dispatch.hpp"
#include "penumbra/memory.hpp"

namespace penumbra::gpu {

struct DeviceInfo {
    uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::string driver;  // driver name and info, e.g. "llvmpipe (Mesa 22.3.6)"
    uint32_t api_version = 0;
    bool usable = false;  // Vulkan 1.3 with dynamic rendering, sync2 and a graphics + compute queue
};

// The optional features Penumbra uses when the device was created with them.
struct EnabledFeatures {
    bool multiview = false;         // VkPhysicalDeviceVulkan11Features::multiview (multiview strategy)
    bool depth_clamp = false;       // VkPhysicalDeviceFeatures::depthClamp
    bool depth_bias_clamp = false;  // VkPhysicalDeviceFeatures::depthBiasClamp
    // The layered strategy's GPU-driven culling: VkPhysicalDeviceFeatures::multiDrawIndirect
    // and drawIndirectFirstInstance, VkPhysicalDeviceVulkan12Features::drawIndirectCount and
    // shaderOutputLayer, all four.
    bool gpu_driven = false;
    // The sun's virtual shadow maps: gpu_driven, VkPhysicalDeviceFeatures::multiViewport and
    // VkPhysicalDeviceVulkan12Features::shaderOutputViewportIndex (each caster is drawn into
    // its page's layer and viewport of the pool).
    bool virtual_pages = false;
};

// The handles a Device is made from.
struct DeviceHandles {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    // A second family whose queue also uses the images and buffers made on this Device
    // (async compute), or VK_QUEUE_FAMILY_IGNORED: with one, they are created shared by both
    // families (VK_SHARING_MODE_CONCURRENT) and never change hands.
    uint32_t compute_queue_family = VK_QUEUE_FAMILY_IGNORED;
    VkQueue compute_queue = VK_NULL_HANDLE;
};

class Device {
public:
    // Loads the function table through `get_instance_proc_addr` and reads the device's
    // properties. Checks nothing about features (a ShadowSystem checks what it needs and
    // names what is missing).
    // Images and buffers get their memory from `allocator` (the caller's, which outlives
    // the Device), or with nullptr from the Device's own blocks.
    Device(const DeviceHandles& handles, const EnabledFeatures& features,
           PFN_vkGetInstanceProcAddr get_instance_proc_addr, DeviceMemoryAllocator* allocator = nullptr);
    virtual ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    VkInstance instance() const { return handles_.instance; }
    VkPhysicalDevice physical_device() const { return handles_.physical_device; }
    VkDevice device() const { return handles_.device; }
    VkQueue queue() const { return handles_.queue; }
    uint32_t queue_family() const { return handles_.queue_family; }
    // The async compute queue's family (DeviceHandles::compute_queue_family) and queue.
    uint32_t compute_queue_family() const { return handles_.compute_queue_family; }
    VkQueue compute_queue() const { return handles_.compute_queue; }
    // Whether images and buffers are shared by the two families (a compute family is set).
    bool shares_with_compute() const { return handles_.compute_queue_family != VK_QUEUE_FAMILY_IGNORED; }
    // The two families they are then shared by (VkBufferCreateInfo::pQueueFamilyIndices).
    const std::array<uint32_t, 2>& sharing_families() const { return sharing_families_; }
    const DeviceInfo& info() const { return info_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    bool depth_clamp_supported() const { return features_.depth_clamp; }
    bool depth_bias_clamp_supported() const { return features_.depth_bias_clamp; }
    // 0 when multiview is not enabled.
    uint32_t max_multiview_views() const { return max_multiview_views_; }
    const EnabledFeatures& features() const { return features_; }

    const VulkanFunctions& vk() const { return vk_; }
    const VulkanFunctions* operator->() const { return &vk_; }
    operator VkDevice() const { return handles_.device; }  // NOLINT: `device->vkFoo(device, ...)`

    // A memory type among `type_bits` with all of `properties`; throws VulkanError if none.
    uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags properties) const;
    const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
    // Where images and buffers get their memory (gpu::create_image, gpu::create_buffer).
    DeviceMemoryAllocator& allocator() const { return *allocator_; }
    // Blocks of device memory the Device's own allocator holds (0 with the caller's).
    size_t own_memory_blocks() const;

    // VK_EXT_debug_utils is enabled on the instance: objects get names and passes labels
    // (penumbra/gpu/debug_names.hpp).
    bool debug_names() const { return vk_.vkSetDebugUtilsObjectNameEXT != nullptr; }
    // What the objects the gpu helpers create now are for (gpu::ObjectNames sets it).
    const std::string& object_purpose() const { return object_purpose_; }
    void set_object_purpose(std::string purpose) const { object_purpose_ = std::move(purpose); }

protected:
    // For the library's own device context, which creates the handles first and then calls
    // initialize().
    Device() = default;
    void initialize(const DeviceHandles& handles, const EnabledFeatures& features, uint32_t device_index = 0,
                    DeviceMemoryAllocator* allocator = nullptr);
    VulkanFunctions vk_;

private:
    DeviceHandles handles_;
    std::array<uint32_t, 2> sharing_families_{};  // queue_family, compute_queue_family
    EnabledFeatures features_;
    DeviceInfo info_;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    uint32_t max_multiview_views_ = 0;
    std::unique_ptr<DeviceMemoryAllocator> own_allocator_;  // without the caller's
    DeviceMemoryAllocator* allocator_ = nullptr;
    // Naming state, not the device's: changed while objects are created, hence mutable
    // (a Device, like a ShadowSystem, is used from one thread at a time).
    mutable std::string object_purpose_ = "penumbra";
};

// The queue families of a physical device, in index order.
std::vector<VkQueueFamilyProperties> queue_families(const VulkanFunctions& vk, VkPhysicalDevice device);

// Describes a physical device (name, type, driver, API version, usability).
DeviceInfo describe_physical_device(const VulkanFunctions& vk, VkPhysicalDevice device, uint32_t index);

// The first queue family with graphics and compute, if any.
bool find_graphics_compute_family(const VulkanFunctions& vk, VkPhysicalDevice device, uint32_t& family);

const char* device_type_name(VkPhysicalDeviceType type);
std::string api_version_string(uint32_t version);

}  // namespace penumbra::gpu
