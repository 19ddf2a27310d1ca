#pragma once
// Move-only RAII owners for Vulkan objects. A DeviceHandle destroys its object with the
// device's own destroy function (from its function table, gpu/dispatch.hpp), named by
// the member pointer given as a template argument. The owner that creates GPU work is
// responsible for waiting on it before handles go out of scope (the CLI's renderer waits
// for its fence; a ShadowSystem keeps retired objects until their frames are done).
#include <vulkan/vulkan.h>

#include <utility>

#include "penumbra/gpu/device.hpp"

namespace penumbra::gpu {

template <typename Handle, auto Destroy>
class DeviceHandle {
public:
    using DestroyFunction = void(VKAPI_PTR*)(VkDevice, Handle, const VkAllocationCallbacks*);

    DeviceHandle() = default;
    DeviceHandle(const Device& device, Handle handle)
        : device_(device.device()), destroy_(device.vk().*Destroy), handle_(handle) {}
    ~DeviceHandle() { reset(); }

    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    DeviceHandle(DeviceHandle&& other) noexcept
        : device_(other.device_), destroy_(other.destroy_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
    DeviceHandle& operator=(DeviceHandle&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = other.device_;
            destroy_ = other.destroy_;
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }

    Handle get() const { return handle_; }
    operator Handle() const { return handle_; }  // NOLINT: handles pass straight into vk calls
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

    void reset() {
        if (handle_ != VK_NULL_HANDLE) destroy_(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    DestroyFunction destroy_ = nullptr;
    Handle handle_ = VK_NULL_HANDLE;
};

using UniqueBuffer = DeviceHandle<VkBuffer, &VulkanFunctions::vkDestroyBuffer>;
using UniqueImage = DeviceHandle<VkImage, &VulkanFunctions::vkDestroyImage>;
using UniqueImageView = DeviceHandle<VkImageView, &VulkanFunctions::vkDestroyImageView>;
using UniqueMemory = DeviceHandle<VkDeviceMemory, &VulkanFunctions::vkFreeMemory>;
using UniqueSampler = DeviceHandle<VkSampler, &VulkanFunctions::vkDestroySampler>;
using UniqueShaderModule = DeviceHandle<VkShaderModule, &VulkanFunctions::vkDestroyShaderModule>;
using UniquePipeline = DeviceHandle<VkPipeline, &VulkanFunctions::vkDestroyPipeline>;
using UniquePipelineLayout = DeviceHandle<VkPipelineLayout, &VulkanFunctions::vkDestroyPipelineLayout>;
using UniqueDescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, &VulkanFunctions::vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = DeviceHandle<VkDescriptorPool, &VulkanFunctions::vkDestroyDescriptorPool>;
using UniqueCommandPool = DeviceHandle<VkCommandPool, &VulkanFunctions::vkDestroyCommandPool>;
using UniqueFence = DeviceHandle<VkFence, &VulkanFunctions::vkDestroyFence>;
using UniqueSemaphore = DeviceHandle<VkSemaphore, &VulkanFunctions::vkDestroySemaphore>;
using UniqueQueryPool = DeviceHandle<VkQueryPool, &VulkanFunctions::vkDestroyQueryPool>;
using UniqueRenderPass = DeviceHandle<VkRenderPass, &VulkanFunctions::vkDestroyRenderPass>;
using UniqueFramebuffer = DeviceHandle<VkFramebuffer, &VulkanFunctions::vkDestroyFramebuffer>;
using UniqueSwapchain = DeviceHandle<VkSwapchainKHR, &VulkanFunctions::vkDestroySwapchainKHR>;

}  // namespace penumbra::gpu
