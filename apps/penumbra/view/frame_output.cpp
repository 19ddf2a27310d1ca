#include "frame_output.hpp"

#include <cstring>

#include "penumbra/gpu/barriers.hpp"

namespace penumbra::view {
namespace {

constexpr VkImageAspectFlags kColor = VK_IMAGE_ASPECT_COLOR_BIT;

void blit(VkCommandBuffer cmd, const gpu::Image& color, const present::Frame& frame) {
    VkImageBlit region{};
    region.srcSubresource = {kColor, 0, 0, 1};
    region.srcOffsets[1] = {static_cast<int32_t>(color.desc.width), static_cast<int32_t>(color.desc.height), 1};
    region.dstSubresource = {kColor, 0, 0, 1};
    region.dstOffsets[1] = {static_cast<int32_t>(frame.extent.width), static_cast<int32_t>(frame.extent.height), 1};
    const bool same_size = color.desc.width == frame.extent.width && color.desc.height == frame.extent.height;
    vkCmdBlitImage(cmd, color.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, frame.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, same_size ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
}

}  // namespace

void FrameOutput::record_scene(VkCommandBuffer cmd, const gpu::Image& color, const present::Frame& frame,
                               bool capture) {
    gpu::transition(context_, cmd, color, gpu::ImageState::TransferSrc, gpu::ImageState::BlitSrc);
    gpu::transition(context_, cmd, frame.image, kColor, 1, gpu::ImageState::SwapchainAcquired,
                    gpu::ImageState::BlitDst);
    blit(cmd, color, frame);
    if (!capture) {
        gpu::transition(context_, cmd, frame.image, kColor, 1, gpu::ImageState::BlitDst,
                        gpu::ImageState::ColorAttachment);
        return;
    }
    const VkDeviceSize bytes = VkDeviceSize{frame.extent.width} * frame.extent.height * 4;
    if (!capture_buffer_.buffer || capture_buffer_.size < bytes) {
        capture_buffer_ =
            gpu::create_buffer(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryKind::HostReadback);
    }
    gpu::transition(context_, cmd, frame.image, kColor, 1, gpu::ImageState::BlitDst, gpu::ImageState::TransferSrc);
    VkBufferImageCopy region{};
    region.imageSubresource = {kColor, 0, 0, 1};
    region.imageExtent = {frame.extent.width, frame.extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, frame.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, capture_buffer_.get(), 1, &region);
    gpu::transfer_to_host_barrier(context_, cmd);
    gpu::transition(context_, cmd, frame.image, kColor, 1, gpu::ImageState::TransferSrc,
                    gpu::ImageState::ColorAttachment);
    captured_extent_ = frame.extent;
    captured_format_ = frame.format;
}

void FrameOutput::record_present_transition(VkCommandBuffer cmd, const present::Frame& frame) const {
    gpu::transition(context_, cmd, frame.image, kColor, 1, gpu::ImageState::ColorAttachment,
                    gpu::ImageState::PresentSrc);
}

std::vector<uint8_t> FrameOutput::captured_rgba() const {
    const size_t bytes = size_t{captured_extent_.width} * captured_extent_.height * 4;
    std::vector<uint8_t> pixels(bytes);
    std::memcpy(pixels.data(), capture_buffer_.mapped, bytes);
    const bool bgra = captured_format_ == VK_FORMAT_B8G8R8A8_SRGB || captured_format_ == VK_FORMAT_B8G8R8A8_UNORM;
    if (bgra) {
        for (size_t i = 0; i < bytes; i += 4) std::swap(pixels[i], pixels[i + 2]);
    }
    return pixels;
}

}  // namespace penumbra::view
