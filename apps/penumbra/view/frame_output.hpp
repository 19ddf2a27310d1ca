#pragma once
// Puts the renderer's colour target on the window: records the blit into the swapchain
// image, optionally a copy of the result into a readback buffer (screenshots, taken
// before the panel is drawn so that they hold the scene alone), and the final transition
// for presentation. The image states follow gpu::transition's table:
//   swapchain image: SwapchainAcquired -> BlitDst [-> TransferSrc] -> ColorAttachment
//                    (the panel draws here) -> PresentSrc
//   colour target:   TransferSrc (as Renderer::render leaves it) -> BlitSrc
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "penumbra/gpu/resources.hpp"
#include "present/presenter.hpp"
#include "renderer/app_context.hpp"

namespace penumbra::view {

class FrameOutput {
public:
    explicit FrameOutput(const renderer::AppContext& context) : context_(context) {}

    // Blits `color` over the whole swapchain image (scaled if the sizes differ) and leaves
    // the image in ColorAttachment. With `capture`, the blitted image is also copied out.
    void record_scene(VkCommandBuffer cmd, const gpu::Image& color, const present::Frame& frame, bool capture);
    // ColorAttachment -> PresentSrc.
    void record_present_transition(VkCommandBuffer cmd, const present::Frame& frame) const;

    // After the frame's submission has completed: the captured image as 8-bit sRGB RGBA,
    // row 0 at the top (swapchain BGRA is swizzled).
    std::vector<uint8_t> captured_rgba() const;
    VkExtent2D captured_extent() const { return captured_extent_; }

private:
    const renderer::AppContext& context_;
    gpu::Buffer capture_buffer_;
    VkExtent2D captured_extent_{};
    VkFormat captured_format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace penumbra::view
