#pragma once
// The Vulkan device layer's root: instance (optionally with the Khronos validation
// layer and synchronization validation), physical-device choice, logical device,
// one graphics queue and a command pool. Headless by default: no surface, no swapchain;
// ContextOptions::presentation turns on what a window needs (src/present).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/handle.hpp"

namespace penumbra::gpu {

struct DeviceInfo {
    uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::string driver;  // driver name and info, e.g. "llvmpipe (Mesa 22.3.6)"
    uint32_t api_version = 0;
    bool usable = false;  // Vulkan 1.3 with dynamic rendering, sync2 and a graphics queue
};

const char* device_type_name(VkPhysicalDeviceType type);
std::string api_version_string(uint32_t version);

// Messages reported by the validation layer (warnings and errors only).
struct ValidationLog {
    std::vector<std::string> messages;
    bool clean() const { return messages.empty(); }
};

struct ContextOptions {
    bool validation = false;      // Khronos validation layer + synchronization validation
    std::string device_selector;  // "" = best device; an index or a case-insensitive name substring
    // Where validation messages go; shared so that messages reported while the device and
    // instance are destroyed (leaks) can still be read after the Context is gone.
    std::shared_ptr<ValidationLog> log = std::make_shared<ValidationLog>();
    // Set for a window: the instance gets `instance_extensions` (e.g. from
    // glfwGetRequiredInstanceExtensions), the device VK_KHR_swapchain, and the queue is a
    // graphics family for which `can_present` holds (e.g. glfwGetPhysicalDevicePresentationSupport).
    struct Presentation {
        std::vector<std::string> instance_extensions;
        std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)> can_present;
    };
    std::optional<Presentation> presentation;  // nullopt = headless (no WSI extensions)
};

// Lists the physical devices. Throws penumbra::DeviceError when no Vulkan driver is present.
std::vector<DeviceInfo> list_devices();

class Context {
public:
    // Throws penumbra::DeviceError when no usable device exists or the selector matches none.
    explicit Context(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    const DeviceInfo& info() const { return info_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    bool depth_clamp_supported() const { return depth_clamp_; }
    bool depth_bias_clamp_supported() const { return depth_bias_clamp_; }
    uint32_t max_multiview_views() const { return max_multiview_views_; }
    bool validation_enabled() const { return validation_enabled_; }
    bool presentation_enabled() const { return presentation_.has_value(); }
    const ValidationLog& validation_log() const { return *validation_log_; }

    uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags properties) const;

    // Records commands into a fresh primary command buffer, submits it and waits.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

private:
    void create_instance(bool validation);
    void pick_physical_device(const std::string& selector);
    void pick_present_queue_family();
    void create_device();
    void release();  // destroys whatever was created, in reverse order

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    DeviceInfo info_;
    VkPhysicalDeviceProperties properties_{};
    bool depth_clamp_ = false;
    bool depth_bias_clamp_ = false;
    uint32_t max_multiview_views_ = 0;
    bool validation_enabled_ = false;
    std::shared_ptr<ValidationLog> validation_log_;
    std::optional<ContextOptions::Presentation> presentation_;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
};

}  // namespace penumbra::gpu
