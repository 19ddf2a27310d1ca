#include "penumbra/gpu/features.hpp"

namespace penumbra::gpu {

FeatureChain read_feature_chain(const VkPhysicalDeviceFeatures2& features) {
    FeatureChain chain;
    chain.depth_clamp = features.features.depthClamp == VK_TRUE;
    chain.depth_bias_clamp = features.features.depthBiasClamp == VK_TRUE;
    chain.multi_draw_indirect = features.features.multiDrawIndirect == VK_TRUE;
    chain.draw_indirect_first_instance = features.features.drawIndirectFirstInstance == VK_TRUE;
    chain.multi_viewport = features.features.multiViewport == VK_TRUE;
    for (auto* next = static_cast<const VkBaseInStructure*>(features.pNext); next != nullptr; next = next->pNext) {
        switch (next->sType) {
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES:
                chain.multiview |=
                    reinterpret_cast<const VkPhysicalDeviceVulkan11Features*>(next)->multiview == VK_TRUE;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES: {
                const auto* features12 = reinterpret_cast<const VkPhysicalDeviceVulkan12Features*>(next);
                chain.draw_indirect_count |= features12->drawIndirectCount == VK_TRUE;
                chain.shader_output_layer |= features12->shaderOutputLayer == VK_TRUE;
                chain.shader_output_viewport_index |= features12->shaderOutputViewportIndex == VK_TRUE;
                break;
            }
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
                const auto* features13 = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(next);
                chain.dynamic_rendering |= features13->dynamicRendering == VK_TRUE;
                chain.synchronization2 |= features13->synchronization2 == VK_TRUE;
                break;
            }
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES:
                chain.multiview |=
                    reinterpret_cast<const VkPhysicalDeviceMultiviewFeatures*>(next)->multiview == VK_TRUE;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
                chain.dynamic_rendering |=
                    reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(next)->dynamicRendering ==
                    VK_TRUE;
                break;
            case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
                chain.synchronization2 |=
                    reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(next)->synchronization2 ==
                    VK_TRUE;
                break;
            default:
                break;
        }
    }
    return chain;
}

}  // namespace penumbra::gpu
