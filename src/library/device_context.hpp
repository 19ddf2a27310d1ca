#pragma once
// A Vulkan instance and device created by Penumbra for callers that have none (behind the
// public penumbra::VulkanContext): instance (optionally with the Khronos validation layer
// and synchronization validation), physical-device choice, a device with exactly the
// features Penumbra uses and one graphics + compute queue. Headless by default: no
// surface, no swapchain;
// ContextOptions::presentation turns on what a window needs (the viewer's apps/present).
// A Context is a gpu::Device, so everything that takes a Device takes a Context.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "penumbra/gpu/device.hpp"

namespace penumbra::gpu {

// Messages reported by the validation layer (warnings and errors only).
struct ValidationLog {
    std::vector<std::string> messages;
    bool clean() const { return messages.empty(); }
};

struct ContextOptions {
    bool validation = false;      // Khronos validation layer + synchronization validation
    bool best_practices = false;  // with validation: the layer's best-practices checks too
    std::string device_selector;  // "" = best device; an index or a case-insensitive name substring
    // Where validation messages go; shared so that messages reported while the device and
    // instance are destroyed (leaks) can still be read after the Context is gone.
    std::shared_ptr<ValidationLog> log = std::make_shared<ValidationLog>();
    // Also called with each message as it arrives (e.g. to print it); may be empty.
    std::function<void(const std::string& message)> on_message;
    // Set for a window: the instance gets `instance_extensions` (e.g. from
    // glfwGetRequiredInstanceExtensions), the device VK_KHR_swapchain, and the queue is a
    // graphics family for which `can_present` holds (e.g. glfwGetPhysicalDevicePresentationSupport).
    struct Presentation {
        std::vector<std::string> instance_extensions;
        std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)> can_present;
    };
    std::optional<Presentation> presentation;  // nullopt = headless (no WSI extensions)
    // Also one queue of a family with compute and without graphics, when the device has one.
    bool async_compute = false;
};

// Lists the physical devices. Throws DeviceError when no Vulkan driver is present.
std::vector<DeviceInfo> list_devices();

class Context : public Device {
public:
    // Throws DeviceError when no usable device exists or the selector matches none.
    explicit Context(const ContextOptions& options);
    ~Context() override;

    bool validation_enabled() const { return validation_enabled_; }
    // ContextOptions::async_compute's queue and family; VK_QUEUE_FAMILY_IGNORED without one.
    // The Context's own images and buffers stay exclusive to queue_family().
    uint32_t async_compute_family() const { return compute_family_; }
    VkQueue async_compute_queue() const { return compute_queue_; }
    bool presentation_enabled() const { return presentation_.has_value(); }
    const ValidationLog& validation_log() const { return *validation_log_; }
    const std::shared_ptr<ValidationLog>& shared_validation_log() const { return validation_log_; }

    // Called by the validation layer's messenger.
    void report_validation_message(std::string message) const;

private:
    void create_instance(bool validation, bool best_practices);
    uint32_t pick_physical_device(const std::string& selector);
    void pick_present_queue_family();
    void pick_async_compute_family();
    EnabledFeatures create_device();
    void release();  // destroys whatever was created, in reverse order

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    uint32_t compute_family_ = VK_QUEUE_FAMILY_IGNORED;
    VkQueue compute_queue_ = VK_NULL_HANDLE;
    bool validation_enabled_ = false;
    std::shared_ptr<ValidationLog> validation_log_;
    std::function<void(const std::string& message)> on_message_;
    std::optional<ContextOptions::Presentation> presentation_;
};

}  // namespace penumbra::gpu
