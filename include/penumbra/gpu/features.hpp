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
};

// Walks the pNext chain; structures it does not know are skipped.
FeatureChain read_feature_chain(const VkPhysicalDeviceFeatures2& features);

}  // namespace penumbra::gpu
