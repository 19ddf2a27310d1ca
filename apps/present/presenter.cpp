#include "present/presenter.hpp"

#include "penumbra/gpu/check.hpp"

namespace penumbra::present {
namespace {

UniqueSemaphore create_semaphore(const gpu::Device& device) {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &semaphore));
    return UniqueSemaphore(device, semaphore);
}

bool same_extent(VkExtent2D a, VkExtent2D b) { return a.width == b.width && a.height == b.height; }

}  // namespace

Presenter::Presenter(const gpu::Device& context, const Window& window, const Surface& surface,
                     const SwapchainOptions& options)
    : context_(context), window_(window), surface_(surface.get()), options_(options) {
    const gpu::Device& device = context;
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool));
    pool_ = gpu::UniqueCommandPool(device, pool);
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    PENUMBRA_VK_CHECK(vkAllocateCommandBuffers(device, &allocate, &cmd_));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // no frame in flight yet
    VkFence fence = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateFence(device, &fence_info, nullptr, &fence));
    fence_ = gpu::UniqueFence(device, fence);
    image_acquired_ = create_semaphore(device);
    recreate(window.framebuffer_size());
}

Presenter::~Presenter() {
    if (context_.device()) vkDeviceWaitIdle(context_.device());
}

void Presenter::recreate(VkExtent2D extent) {
    // Nothing may still use the old images or semaphores.
    PENUMBRA_VK_CHECK(vkDeviceWaitIdle(context_.device()));
    std::unique_ptr<Swapchain> old = std::move(swapchain_);
    swapchain_ = std::make_unique<Swapchain>(context_, surface_, extent, options_, old ? old->get() : VK_NULL_HANDLE);
    old.reset();
    present_ready_.clear();
    for (size_t i = 0; i < swapchain_->images().size(); ++i) present_ready_.push_back(create_semaphore(context_));
    requested_extent_ = extent;
    ++generation_;
}

void Presenter::wait_for_last_frame() const {
    const VkFence fence = fence_;
    VkResult wait = VK_TIMEOUT;
    // A fence wait can legitimately time out on a slow CPU device; keep waiting.
    while (wait == VK_TIMEOUT) wait = vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, 10'000'000'000ull);
    PENUMBRA_VK_CHECK(wait);
}

std::optional<Frame> Presenter::begin_frame() {
    wait_for_last_frame();
    const VkExtent2D window_extent = window_.framebuffer_size();
    if (window_extent.width == 0 || window_extent.height == 0) return std::nullopt;  // minimised
    // Compared with the size last asked for, not the swapchain's (the surface may round it),
    // so that a surface that disagrees with the window cannot cause a re-creation every frame.
    if (!same_extent(window_extent, requested_extent_)) recreate(window_extent);

    uint32_t index = 0;
    const VkResult acquired = vkAcquireNextImageKHR(context_.device(), swapchain_->get(), UINT64_MAX, image_acquired_,
                                                    VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        recreate(window_extent);
        return std::nullopt;
    }
    if (acquired != VK_SUBOPTIMAL_KHR) PENUMBRA_VK_CHECK(acquired);  // suboptimal: present, then recreate

    const VkFence fence = fence_;
    PENUMBRA_VK_CHECK(vkResetFences(context_.device(), 1, &fence));
    PENUMBRA_VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    PENUMBRA_VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    return Frame{cmd_,
                 index,
                 swapchain_->images()[index],
                 swapchain_->views()[index].get(),
                 swapchain_->extent(),
                 swapchain_->format()};
}

void Presenter::end_frame(const Frame& frame) {
    PENUMBRA_VK_CHECK(vkEndCommandBuffer(frame.cmd));
    // Everything waits for the acquire (ImageState::SwapchainAcquired chains with this stage).
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = image_acquired_;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = present_ready_[frame.image_index];
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = frame.cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = 1;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &signal;
    PENUMBRA_VK_CHECK(vkQueueSubmit2(context_.queue(), 1, &submit, fence_.get()));

    const VkSemaphore ready = present_ready_[frame.image_index];
    const VkSwapchainKHR swapchain = swapchain_->get();
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &ready;
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain;
    present.pImageIndices = &frame.image_index;
    const VkResult presented = vkQueuePresentKHR(context_.queue(), &present);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
        const VkExtent2D extent = window_.framebuffer_size();
        if (extent.width > 0 && extent.height > 0) recreate(extent);
        return;
    }
    PENUMBRA_VK_CHECK(presented);
}

}  // namespace penumbra::present
