#pragma once
// The tools' Vulkan device: Penumbra's VulkanContext (the library's helper for callers
// without a device, docs/library.md) seen through the device layer (gpu::Device), plus a
// command pool for one-off uploads. The tools use it exactly as any caller would use its
// own device: the ShadowSystem gets context.device_desc().
#include <functional>

#include "penumbra/device.hpp"
#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/one_time_commands.hpp"

namespace penumbra::renderer {

// Holds the VulkanContext so that it is constructed before the gpu::Device that views it.
class VulkanContextHolder {
protected:
    explicit VulkanContextHolder(const VulkanContextOptions& options) : vulkan_(options) {}
    VulkanContext vulkan_;
};

class AppContext : private VulkanContextHolder, public gpu::Device {
public:
    // Throws DeviceError (no usable device, selector matches none, validation layer missing).
    // Validation messages go to options.validation_log; without on_validation_message they
    // are also printed to stderr as they arrive ("penumbra: validation error: ...").
    explicit AppContext(VulkanContextOptions options);

    const DeviceDesc& device_desc() const { return vulkan_.device_desc(); }
    const PhysicalDeviceInfo& physical_device_info() const { return vulkan_.physical_device_info(); }
    bool validation_enabled() const { return vulkan_.validation_enabled(); }

    // One-off uploads on the queue (create_texture_rgba8, create_buffer_with_data).
    const gpu::OneTimeCommands& one_time() const { return one_time_; }
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
        one_time_.submit_and_wait(record);
    }

private:
    gpu::OneTimeCommands one_time_;
};

}  // namespace penumbra::renderer
