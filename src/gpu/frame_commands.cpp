#include "gpu/frame_commands.hpp"

#include "gpu/check.hpp"

namespace penumbra::gpu {

FrameCommands::FrameCommands(const Context& context) : context_(context) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateCommandPool(context.device(), &pool_info, nullptr, &pool));
    pool_ = UniqueCommandPool(context.device(), pool);

    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    PENUMBRA_VK_CHECK(vkAllocateCommandBuffers(context.device(), &allocate, &cmd_));

    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateFence(context.device(), &fence_info, nullptr, &fence));
    fence_ = UniqueFence(context.device(), fence);
}

void FrameCommands::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
    const VkDevice device = context_.device();
    const VkFence fence = fence_;
    PENUMBRA_VK_CHECK(vkResetFences(device, 1, &fence));
    PENUMBRA_VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    PENUMBRA_VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    record(cmd_);
    PENUMBRA_VK_CHECK(vkEndCommandBuffer(cmd_));

    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd_;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    PENUMBRA_VK_CHECK(vkQueueSubmit2(context_.queue(), 1, &submit, fence));
    // A fence wait can legitimately time out on a slow CPU device; keep waiting.
    VkResult wait = VK_TIMEOUT;
    while (wait == VK_TIMEOUT) wait = vkWaitForFences(device, 1, &fence, VK_TRUE, 10'000'000'000ull);
    PENUMBRA_VK_CHECK(wait);
}

}  // namespace penumbra::gpu
