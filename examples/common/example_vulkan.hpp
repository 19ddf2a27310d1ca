#pragma once
// What both examples need besides Penumbra, written the way an application would: a
// Vulkan 1.3 instance and device of their own (created with exactly the features
// docs/library.md lists), buffers and images with memory, one-shot command submission and
// a 16-bit grayscale PNG writer. Deliberately plain: the interesting part is how little
// Penumbra asks of it (see minimal/main.cpp and deferred/main.cpp).
#include <vulkan/vulkan.h>
#include <penumbra/device.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace example {

// Warnings and errors the validation layer reported (also while devices were destroyed).
uint32_t validation_message_count();

// Throws std::runtime_error naming the call when it fails.
void check(VkResult result, const char* call);
#define EXAMPLE_CHECK(call) ::example::check((call), #call)

struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    // With async compute, where the device has a family with compute and without graphics:
    // its queue and a command pool for it (VK_QUEUE_FAMILY_IGNORED / null otherwise).
    uint32_t compute_family = VK_QUEUE_FAMILY_IGNORED;
    VkQueue compute_queue = VK_NULL_HANDLE;
    VkCommandPool compute_pool = VK_NULL_HANDLE;
    // The feature chain vkCreateDevice got: Penumbra reads it (DeviceDesc::enabled_features).
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};

    // `validation`: the Khronos validation layer with synchronization validation.
    explicit Device(bool validation, bool async_compute = false);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // What Penumbra is told about this device: the handles, the instance's API version and
    // the feature chain vkCreateDevice got (Penumbra checks it for what it requires).
    penumbra::DeviceDesc penumbra_desc() const;

    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags properties) const;
    // Records, submits and waits.
    void submit(const std::function<void(VkCommandBuffer)>& record) const;
};

struct Buffer {
    const Device* device = nullptr;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    Buffer(const Device& owner, VkDeviceSize size, VkBufferUsageFlags usage, const void* data = nullptr);
    ~Buffer();
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
};

struct Image {
    const Device* device = nullptr;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    Image(const Device& owner, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage,
          VkImageAspectFlags aspect);
    ~Image();
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;
};

// One image layout transition (synchronization2).
void barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
             VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage,
             VkAccessFlags2 dst_access);

// Makes copy writes (into host-visible buffers) visible to the host once the submission's
// wait returns.
void host_read_barrier(VkCommandBuffer cmd);

VkShaderModule shader_module(const Device& device, const uint32_t* code, size_t bytes);

// Row 0 at the top; 65535 white.
void write_png16(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint16_t>& pixels);

}  // namespace example
