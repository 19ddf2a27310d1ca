#pragma once
// Presents frames to a window: owns the surface's swapchain, the frame's command buffer,
// the acquire semaphore, one present semaphore per swapchain image and the frame fence,
// and recreates the swapchain when the window is resized or the swapchain is out of date.
// One frame in flight: begin_frame() waits for the previous frame's fence.
//
//   present::Presenter presenter(context, window, surface, {});
//   if (std::optional<present::Frame> frame = presenter.begin_frame()) {
//       ... record into frame->cmd: image frame->image is in ImageState::SwapchainAcquired,
//           and must end in ImageState::PresentSrc ...
//       presenter.end_frame(*frame);
//   }
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"
#include "present/swapchain.hpp"
#include "present/window.hpp"

namespace penumbra::present {

struct Frame {
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // recording has begun
    uint32_t image_index = 0;
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkExtent2D extent{};
    VkFormat format = VK_FORMAT_UNDEFINED;
};

using gpu::UniqueSemaphore;

class Presenter {
public:
    Presenter(const gpu::Device& context, const Window& window, const Surface& surface,
              const SwapchainOptions& options);
    ~Presenter();  // waits for the device to idle
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // Waits for the previous frame, recreates the swapchain if the window size changed,
    // acquires an image and begins the command buffer. nullopt when there is nothing to
    // draw into: the window is minimised, or the swapchain was out of date and has been
    // recreated (the caller simply tries again next frame).
    std::optional<Frame> begin_frame();
    // Ends the command buffer, submits it and presents the image; an out-of-date or
    // suboptimal swapchain is recreated.
    void end_frame(const Frame& frame);
    // Waits until the last submitted frame has finished on the GPU.
    void wait_for_last_frame() const;

    const Swapchain& swapchain() const { return *swapchain_; }
    // Incremented on every recreation, so that objects built on the swapchain's images
    // (framebuffers) know to rebuild.
    uint64_t generation() const { return generation_; }

private:
    void recreate(VkExtent2D extent);

    const gpu::Device& context_;
    const Window& window_;
    VkSurfaceKHR surface_;
    SwapchainOptions options_;
    std::unique_ptr<Swapchain> swapchain_;
    std::vector<UniqueSemaphore> present_ready_;  // per swapchain image
    UniqueSemaphore image_acquired_;
    gpu::UniqueCommandPool pool_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    gpu::UniqueFence fence_;         // signalled: no frame in flight
    VkExtent2D requested_extent_{};  // the window size the swapchain was last made for
    uint64_t generation_ = 0;
};

}  // namespace penumbra::present
