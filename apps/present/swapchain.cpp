#include "present/swapchain.hpp"

#include <algorithm>

#include "penumbra/gpu/check.hpp"

namespace penumbra::present {
namespace {

VkSurfaceFormatKHR choose_format(VkPhysicalDevice device, VkSurfaceKHR surface) {
    uint32_t count = 0;
    PENUMBRA_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    PENUMBRA_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &count, formats.data()));
    if (formats.empty()) throw VulkanError("the window surface offers no formats", VK_ERROR_FORMAT_NOT_SUPPORTED);
    // The renderer's colour target is sRGB-encoded; an sRGB swapchain keeps a blit exact.
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB}) {
        for (const VkSurfaceFormatKHR& format : formats) {
            if (format.format == wanted && format.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return format;
        }
    }
    return formats.front();
}

VkPresentModeKHR choose_present_mode(VkPhysicalDevice device, VkSurfaceKHR surface, bool vsync) {
    if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
    uint32_t count = 0;
    PENUMBRA_VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(device, surface, &count, nullptr));
    std::vector<VkPresentModeKHR> modes(count);
    PENUMBRA_VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(device, surface, &count, modes.data()));
    for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
        if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
    }
    return VK_PRESENT_MODE_FIFO_KHR;
}

VkSurfaceCapabilitiesKHR capabilities_of(const gpu::Device& context, VkSurfaceKHR surface) {
    VkSurfaceCapabilitiesKHR capabilities{};
    PENUMBRA_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context.physical_device(), surface, &capabilities));
    return capabilities;
}

VkExtent2D clamp_extent(const VkSurfaceCapabilitiesKHR& capabilities, VkExtent2D wanted) {
    // 0xFFFFFFFF: the surface size follows the swapchain's.
    if (capabilities.currentExtent.width != UINT32_MAX) return capabilities.currentExtent;
    return {std::clamp(wanted.width, capabilities.minImageExtent.width, capabilities.maxImageExtent.width),
            std::clamp(wanted.height, capabilities.minImageExtent.height, capabilities.maxImageExtent.height)};
}

gpu::UniqueImageView create_view(const gpu::Device& device, VkImage image, VkFormat format) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image;
    info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    info.format = format;
    info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateImageView(device, &info, nullptr, &view));
    return gpu::UniqueImageView(device, view);
}

}  // namespace

VkExtent2D surface_extent(const gpu::Device& context, VkSurfaceKHR surface, VkExtent2D fallback) {
    return clamp_extent(capabilities_of(context, surface), fallback);
}

Swapchain::Swapchain(const gpu::Device& context, VkSurfaceKHR surface, VkExtent2D extent,
                     const SwapchainOptions& options, VkSwapchainKHR old_swapchain)
    : device_(context) {
    const VkSurfaceCapabilitiesKHR capabilities = capabilities_of(context, surface);
    const VkSurfaceFormatKHR format = choose_format(context.physical_device(), surface);
    const VkImageUsageFlags wanted_usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const VkImageUsageFlags usage = wanted_usage & capabilities.supportedUsageFlags;
    if (!(usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT) || !(usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT)) {
        throw VulkanError("the window surface does not support transfer-destination colour images",
                          VK_ERROR_FEATURE_NOT_PRESENT);
    }
    readback_ = (usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    format_ = format.format;
    extent_ = clamp_extent(capabilities, extent);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface;
    info.minImageCount = capabilities.minImageCount + 1;
    if (capabilities.maxImageCount > 0) info.minImageCount = std::min(info.minImageCount, capabilities.maxImageCount);
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = capabilities.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (!(capabilities.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)) {
        info.compositeAlpha = VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
    }
    info.presentMode = choose_present_mode(context.physical_device(), surface, options.vsync);
    info.clipped = VK_TRUE;
    info.oldSwapchain = old_swapchain;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    PENUMBRA_VK_CHECK(vkCreateSwapchainKHR(device_, &info, nullptr, &swapchain));
    swapchain_ = gpu::UniqueSwapchain(device_, swapchain);

    uint32_t count = 0;
    PENUMBRA_VK_CHECK(vkGetSwapchainImagesKHR(device_, swapchain_, &count, nullptr));
    images_.resize(count);
    PENUMBRA_VK_CHECK(vkGetSwapchainImagesKHR(device_, swapchain_, &count, images_.data()));
    for (VkImage image : images_) views_.push_back(create_view(device_, image, format_));
}

}  // namespace penumbra::present
