#pragma once
// What a device was created with, read from the VkPhysicalDeviceFeatures2 chain given to
// vkCreateDevice (Vulkan has no query for enabled features).
#include <vulkan/vulkan.h>

namespace penumbra::gpu {

struct FeatureChain {
    bool dynamic_rendering = false;  // Vulkan13Features or DynamicRenderingFeatures
    bool synchronization2 = false;   // Vulkan13Features or Synchronization2Features
    bool multiview = false;          // Vulkan11Features or MultiviewFeatures
    bool depth_clamp = false;        // VkPhysicalDeviceFeatures
    bool depth_bias_clamp = false;
    bool multi_draw_indirect = false;           // VkPhysicalDeviceFeatures
    bool draw_indirect_first_instance = false;  // VkPhysicalDeviceFeatures
    bool draw_indirect_count = false;           // Vulkan12Features
    bool shader_output_layer = false;           // Vulkan12Features
    bool multi_viewport = false;                // VkPhysicalDeviceFeatures
    bool shader_output_viewport_index = false;  // Vulkan12Features
    // Everything the layered strategy's GPU-driven culling needs (EnabledFeatures::gpu_driven).
    bool gpu_driven() const {
        return multi_draw_indirect && draw_indirect_first_instance && draw_indirect_count && shader_output_layer;
    }
    // The virtual shadow maps' page drawing: GPU-driven, each caster sent to its page's layer
    // and viewport of the pool.
    bool virtual_pages() const { return gpu_driven() && multi_viewport && shader_output_viewport_index; }
};

// Walks the pNext chain; structures it does not know are skipped.
FeatureChain read_feature_chain(const VkPhysicalDeviceFeatures2& features);

}  // namespace penumbra::gpu
