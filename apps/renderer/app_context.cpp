#include "renderer/app_context.hpp"

#include <cstdio>

#include "penumbra/gpu/features.hpp"

namespace penumbra::renderer {
namespace {

VulkanContextOptions with_printing(VulkanContextOptions options) {
    if (!options.on_validation_message) {
        options.on_validation_message = [](const std::string& message) {
            std::fprintf(stderr, "penumbra: %s\n", message.c_str());
        };
    }
    return options;
}

gpu::DeviceHandles handles_of(const DeviceDesc& desc) {
    return {desc.instance, desc.physical_device, desc.device, desc.queue, desc.queue_family};
}

gpu::EnabledFeatures features_of(const DeviceDesc& desc) {
    const gpu::FeatureChain chain = gpu::read_feature_chain(*desc.enabled_features);
    return {chain.multiview, chain.depth_clamp, chain.depth_bias_clamp, chain.gpu_driven()};
}

}  // namespace

AppContext::AppContext(VulkanContextOptions options)
    : VulkanContextHolder(with_printing(std::move(options))),
      gpu::Device(handles_of(vulkan_.device_desc()), features_of(vulkan_.device_desc()),
                  vulkan_.device_desc().get_instance_proc_addr),
      one_time_(*this) {}

}  // namespace penumbra::renderer
