#include "penumbra/gpu/one_time_commands.hpp"
#include "penumbra/gpu/debug_names.hpp"

#include "penumbra/gpu/check.hpp"

namespace penumbra::gpu {

OneTimeCommands::OneTimeCommands(const Device& device) : device_(device) {
    VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    info.queueFamilyIndex = device.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateCommandPool(device, &info, nullptr, &pool));
    name_object(device, VK_OBJECT_TYPE_COMMAND_POOL, pool, "command pool");
    pool_ = UniqueCommandPool(device, pool);
}

void OneTimeCommands::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
    const Device& device = device_;
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkAllocateCommandBuffers(device, &allocate, &cmd));
    name_object(device, VK_OBJECT_TYPE_COMMAND_BUFFER, cmd, "command buffer");
    struct FreeOnExit {
        const Device& device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~FreeOnExit() { device->vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } free_on_exit{device, pool_, cmd};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    PENUMBRA_VK_CHECK(device->vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    PENUMBRA_VK_CHECK(device->vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(device->vkCreateFence(device, &fence_info, nullptr, &fence));
    name_object(device, VK_OBJECT_TYPE_FENCE, fence, "fence");
    const UniqueFence owned_fence(device, fence);
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    PENUMBRA_VK_CHECK(device->vkQueueSubmit2(device.queue(), 1, &submit, fence));
    // A fence wait can legitimately time out on a slow CPU device; keep waiting.
    VkResult wait = VK_TIMEOUT;
    while (wait == VK_TIMEOUT) wait = device->vkWaitForFences(device, 1, &fence, VK_TRUE, 10'000'000'000ull);
    PENUMBRA_VK_CHECK(wait);
}

}  // namespace penumbra::gpu
