// VulkanContext: the public face of gpu::Context, the device layer's own instance and
// device, for callers without a renderer of their own.
#include <utility>

#include "library/device_context.hpp"
#include "penumbra/device.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

PhysicalDeviceInfo to_public(const gpu::DeviceInfo& info) {
    return {info.index, info.name, gpu::device_type_name(info.type), info.driver, info.api_version, info.usable};
}

gpu::ContextOptions context_options(const VulkanContextOptions& options) {
    gpu::ContextOptions result;
    result.validation = options.validation;
    result.best_practices = options.best_practices;
    result.device_selector = options.device_selector;
    result.log = std::make_shared<gpu::ValidationLog>();
    // Messages go to the caller's log and callback; the library prints nothing itself.
    result.on_message = [log = options.validation_log,
                         callback = options.on_validation_message](const std::string& message) {
        if (log) log->messages.push_back(message);
        if (callback) callback(message);
    };
    result.async_compute = options.async_compute;
    if (!options.presentation_extensions.empty() || options.can_present) {
        result.presentation = gpu::ContextOptions::Presentation{options.presentation_extensions, options.can_present};
    }
    return result;
}

}  // namespace

struct VulkanContext::State {
    gpu::Context context;
    VkPhysicalDeviceVulkan13Features features13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan11Features features11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    DeviceDesc desc;
    PhysicalDeviceInfo info;

    explicit State(const VulkanContextOptions& options) : context(context_options(options)) {
        // The chain the device was created with, as a caller's DeviceDesc describes it.
        const gpu::EnabledFeatures& enabled = context.features();
        features13.dynamicRendering = VK_TRUE;
        features13.synchronization2 = VK_TRUE;
        const VkBool32 gpu_driven = enabled.gpu_driven ? VK_TRUE : VK_FALSE;
        features12.drawIndirectCount = gpu_driven;
        features12.shaderOutputLayer = gpu_driven;
        features12.shaderOutputViewportIndex = enabled.virtual_pages ? VK_TRUE : VK_FALSE;
        features12.pNext = &features13;
        features11.multiview = enabled.multiview ? VK_TRUE : VK_FALSE;
        features11.pNext = &features12;
        features.pNext = &features11;
        features.features.depthClamp = enabled.depth_clamp ? VK_TRUE : VK_FALSE;
        features.features.depthBiasClamp = enabled.depth_bias_clamp ? VK_TRUE : VK_FALSE;
        features.features.multiDrawIndirect = gpu_driven;
        features.features.drawIndirectFirstInstance = gpu_driven;
        features.features.multiViewport = enabled.virtual_pages ? VK_TRUE : VK_FALSE;
        desc = {
            context.instance(),     context.physical_device(), context.device(), context.queue(),
            context.queue_family(), VK_API_VERSION_1_3,        &features,        context.vk().vkGetInstanceProcAddr};
        desc.compute_queue_family = context.async_compute_family();
        desc.compute_queue = context.async_compute_queue();
        info = to_public(context.info());
    }
};

VulkanContext::VulkanContext(const VulkanContextOptions& options) : state_(std::make_unique<State>(options)) {}

VulkanContext::~VulkanContext() = default;

const DeviceDesc& VulkanContext::device_desc() const { return state_->desc; }

const PhysicalDeviceInfo& VulkanContext::physical_device_info() const { return state_->info; }

bool VulkanContext::validation_enabled() const { return state_->context.validation_enabled(); }

std::vector<PhysicalDeviceInfo> list_physical_devices() {
    std::vector<PhysicalDeviceInfo> result;
    for (const gpu::DeviceInfo& info : gpu::list_devices()) result.push_back(to_public(info));
    return result;
}

std::string vulkan_version_string(uint32_t version) { return gpu::api_version_string(version); }

}  // namespace penumbra
