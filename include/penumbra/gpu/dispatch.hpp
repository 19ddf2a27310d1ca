#pragma once
// Every Vulkan function Penumbra calls, loaded through the caller's vkGetInstanceProcAddr
// (or the Vulkan loader's when the caller has none), so that the library works on a
// device created through any loader, volk included. The library and the device layer are
// compiled with VK_NO_PROTOTYPES: a call that bypasses this table does not compile.
//
// One table per gpu::Device: device-level functions come from vkGetDeviceProcAddr for
// that device (no loader trampoline), so two devices never share device functions.
#include <vulkan/vulkan.h>

namespace penumbra::gpu {

// Functions queried with a null instance (Vulkan spec, vkGetInstanceProcAddr).
#define PENUMBRA_VK_GLOBAL_FUNCTIONS(X) \
    X(vkCreateInstance)                 \
    X(vkEnumerateInstanceLayerProperties)

#define PENUMBRA_VK_INSTANCE_FUNCTIONS(X)        \
    X(vkDestroyInstance)                         \
    X(vkEnumeratePhysicalDevices)                \
    X(vkEnumerateDeviceExtensionProperties)      \
    X(vkGetPhysicalDeviceProperties)             \
    X(vkGetPhysicalDeviceProperties2)            \
    X(vkGetPhysicalDeviceFeatures)               \
    X(vkGetPhysicalDeviceFeatures2)              \
    X(vkGetPhysicalDeviceFormatProperties)       \
    X(vkGetPhysicalDeviceMemoryProperties)       \
    X(vkGetPhysicalDeviceQueueFamilyProperties)  \
    X(vkCreateDevice)                            \
    X(vkGetDeviceProcAddr)                       \
    X(vkCreateDebugUtilsMessengerEXT)            \
    X(vkDestroyDebugUtilsMessengerEXT)           \
    X(vkSetDebugUtilsObjectNameEXT)              \
    X(vkCmdBeginDebugUtilsLabelEXT)              \
    X(vkCmdEndDebugUtilsLabelEXT)                \
    X(vkDestroySurfaceKHR)                       \
    X(vkGetPhysicalDeviceSurfaceCapabilitiesKHR) \
    X(vkGetPhysicalDeviceSurfaceFormatsKHR)      \
    X(vkGetPhysicalDeviceSurfacePresentModesKHR)

// Vulkan 1.3 core device functions: a device without one of them is not usable.
#define PENUMBRA_VK_DEVICE_FUNCTIONS(X) \
    X(vkDestroyDevice)                  \
    X(vkGetDeviceQueue)                 \
    X(vkDeviceWaitIdle)                 \
    X(vkQueueWaitIdle)                  \
    X(vkQueueSubmit2)                   \
    X(vkAllocateMemory)                 \
    X(vkFreeMemory)                     \
    X(vkMapMemory)                      \
    X(vkCreateBuffer)                   \
    X(vkDestroyBuffer)                  \
    X(vkGetBufferMemoryRequirements)    \
    X(vkBindBufferMemory)               \
    X(vkCreateImage)                    \
    X(vkDestroyImage)                   \
    X(vkGetImageMemoryRequirements)     \
    X(vkBindImageMemory)                \
    X(vkCreateImageView)                \
    X(vkDestroyImageView)               \
    X(vkCreateSampler)                  \
    X(vkDestroySampler)                 \
    X(vkCreateShaderModule)             \
    X(vkDestroyShaderModule)            \
    X(vkCreateGraphicsPipelines)        \
    X(vkCreateComputePipelines)         \
    X(vkDestroyPipeline)                \
    X(vkCreatePipelineLayout)           \
    X(vkDestroyPipelineLayout)          \
    X(vkCreateDescriptorSetLayout)      \
    X(vkDestroyDescriptorSetLayout)     \
    X(vkCreateDescriptorPool)           \
    X(vkDestroyDescriptorPool)          \
    X(vkAllocateDescriptorSets)         \
    X(vkFreeDescriptorSets)             \
    X(vkUpdateDescriptorSets)           \
    X(vkCreateCommandPool)              \
    X(vkDestroyCommandPool)             \
    X(vkAllocateCommandBuffers)         \
    X(vkFreeCommandBuffers)             \
    X(vkResetCommandBuffer)             \
    X(vkBeginCommandBuffer)             \
    X(vkEndCommandBuffer)               \
    X(vkCreateFence)                    \
    X(vkDestroyFence)                   \
    X(vkResetFences)                    \
    X(vkWaitForFences)                  \
    X(vkCreateSemaphore)                \
    X(vkDestroySemaphore)               \
    X(vkDestroyRenderPass)              \
    X(vkDestroyFramebuffer)             \
    X(vkCreateQueryPool)                \
    X(vkDestroyQueryPool)               \
    X(vkGetQueryPoolResults)            \
    X(vkCmdPipelineBarrier2)            \
    X(vkCmdBeginRendering)              \
    X(vkCmdEndRendering)                \
    X(vkCmdBindPipeline)                \
    X(vkCmdBindDescriptorSets)          \
    X(vkCmdBindVertexBuffers)           \
    X(vkCmdBindVertexBuffers2)          \
    X(vkCmdBindIndexBuffer)             \
    X(vkCmdPushConstants)               \
    X(vkCmdSetViewport)                 \
    X(vkCmdSetScissor)                  \
    X(vkCmdSetDepthBias)                \
    X(vkCmdSetCullMode)                 \
    X(vkCmdSetFrontFace)                \
    X(vkCmdDraw)                        \
    X(vkCmdDrawIndexed)                 \
    X(vkCmdDrawIndexedIndirectCount)    \
    X(vkCmdDrawIndirect)                \
    X(vkCmdFillBuffer)                  \
    X(vkCmdUpdateBuffer)                \
    X(vkCmdDispatch)                    \
    X(vkCmdDispatchIndirect)            \
    X(vkCmdCopyBuffer)                  \
    X(vkCmdCopyBufferToImage)           \
    X(vkCmdCopyImageToBuffer)           \
    X(vkCmdBlitImage)                   \
    X(vkCmdCopyImage)                   \
    X(vkCmdClearDepthStencilImage)      \
    X(vkCmdClearColorImage)             \
    X(vkCmdClearAttachments)            \
    X(vkCmdResetQueryPool)              \
    X(vkCmdWriteTimestamp2)

// Device extension functions: null unless the extension is enabled (VK_KHR_swapchain for
// the window viewer).
#define PENUMBRA_VK_DEVICE_EXTENSION_FUNCTIONS(X) \
    X(vkCreateSwapchainKHR)                       \
    X(vkDestroySwapchainKHR)                      \
    X(vkGetSwapchainImagesKHR)                    \
    X(vkAcquireNextImageKHR)                      \
    X(vkQueuePresentKHR)

#define PENUMBRA_VK_DECLARE_MEMBER(name) PFN_##name name = nullptr;

struct VulkanFunctions {
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
    PENUMBRA_VK_GLOBAL_FUNCTIONS(PENUMBRA_VK_DECLARE_MEMBER)
    PENUMBRA_VK_INSTANCE_FUNCTIONS(PENUMBRA_VK_DECLARE_MEMBER)
    PENUMBRA_VK_DEVICE_FUNCTIONS(PENUMBRA_VK_DECLARE_MEMBER)
    PENUMBRA_VK_DEVICE_EXTENSION_FUNCTIONS(PENUMBRA_VK_DECLARE_MEMBER)
};

#undef PENUMBRA_VK_DECLARE_MEMBER

// The Vulkan loader's vkGetInstanceProcAddr (the libvulkan Penumbra links).
PFN_vkGetInstanceProcAddr loader_instance_proc_addr();

// The global functions (vkCreateInstance, ...) through `get_instance_proc_addr`.
VulkanFunctions load_global_functions(PFN_vkGetInstanceProcAddr get_instance_proc_addr);

// Instance-level functions of `instance`. Extension functions the instance lacks stay null;
// throws DeviceError when a Vulkan 1.0/1.1 core one is missing.
void load_instance_functions(VulkanFunctions& functions, VkInstance instance);

// Device-level functions of `device` (vkGetDeviceProcAddr). Throws DeviceError naming the
// first Vulkan 1.3 core function the device does not provide.
void load_device_functions(VulkanFunctions& functions, VkDevice device);

}  // namespace penumbra::gpu
