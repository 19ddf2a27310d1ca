#pragma once
// A VkSwapchainKHR with its images and views, as a move-less RAII owner. Created for a
// surface and an extent; a replacement is created with the old one passed as
// `old_swapchain` (which the caller destroys afterwards, once the device is idle).
#include <vulkan/vulkan.h>

#include <vector>

#include "penumbra/gpu/device.hpp"
#include "penumbra/gpu/handle.hpp"

namespace penumbra::present {

struct SwapchainOptions {
    // FIFO (vsync) or, when false, MAILBOX / IMMEDIATE if the surface offers them.
    bool vsync = true;
};

class Swapchain {
public:
    // `extent` is used when the surface leaves the size to the swapchain; otherwise the
    // surface's current extent wins. Usage: colour attachment, transfer source and
    // destination (blit in, screenshots out). Prefers an 8-bit sRGB format.
    Swapchain(const gpu::Device& context, VkSurfaceKHR surface, VkExtent2D extent, const SwapchainOptions& options,
              VkSwapchainKHR old_swapchain = VK_NULL_HANDLE);
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    VkSwapchainKHR get() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    const std::vector<VkImage>& images() const { return images_; }
    const std::vector<gpu::UniqueImageView>& views() const { return views_; }
    bool supports_readback() const { return readback_; }  // TRANSFER_SRC usage available

private:
    const gpu::Device& device_;
    gpu::UniqueSwapchain swapchain_;  // destroyed after the views
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    bool readback_ = false;
    std::vector<VkImage> images_;
    std::vector<gpu::UniqueImageView> views_;
};

// The surface's current size in pixels, or nullopt-like {0, 0} when it is minimised.
VkExtent2D surface_extent(const gpu::Device& context, VkSurfaceKHR surface, VkExtent2D fallback);

}  // namespace penumbra::present
