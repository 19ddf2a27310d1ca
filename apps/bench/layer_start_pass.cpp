#include "bench/layer_start_pass.hpp"

#include "penumbra/gpu/barriers.hpp"

namespace penumbra::bench {
namespace {

constexpr VkClearDepthStencilValue kFarPlane{0.0f, 0};  // reverse-Z: no caster

gpu::Image create_depth(const gpu::Device& device, uint32_t resolution, uint32_t layers) {
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_D32_SFLOAT;  // the shadow pass's format
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                 VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    desc.array_view = true;
    return gpu::create_image(device, desc);
}

}  // namespace

LayerStartPass::LayerStartPass(const gpu::Device& device, uint32_t resolution, uint32_t layers)
    : device_(device),
      resolution_(resolution),
      layers_(layers),
      map_(create_depth(device, resolution, layers)),
      source_(create_depth(device, resolution, 1)) {}

void LayerStartPass::record_setup(VkCommandBuffer cmd) const {
    gpu::transition(device_, cmd, source_, gpu::ImageState::Undefined, gpu::ImageState::TransferDst);
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    device_->vkCmdClearDepthStencilImage(cmd, source_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &kFarPlane, 1,
                                         &range);
    gpu::transition(device_, cmd, source_, gpu::ImageState::TransferDst, gpu::ImageState::TransferSrc);
    // The map starts sampled, as a shadow map between frames.
    gpu::transition(device_, cmd, map_, gpu::ImageState::Undefined, gpu::ImageState::ShaderSampled);
}

void LayerStartPass::render_pass_clear(VkCommandBuffer cmd, uint32_t extent) const {
    gpu::transition(device_, cmd, map_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::DepthAttachment);
    for (uint32_t layer = 0; layer < layers_; ++layer) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = map_.layer_views[layer];
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = kFarPlane;
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {extent, extent}};
        info.layerCount = 1;
        info.pDepthAttachment = &depth;
        device_->vkCmdBeginRendering(cmd, &info);
        device_->vkCmdEndRendering(cmd);
    }
    gpu::transition(device_, cmd, map_, gpu::ImageState::DepthAttachment, gpu::ImageState::ShaderSampled);
}

void LayerStartPass::clear_image(VkCommandBuffer cmd) const {
    gpu::transition(device_, cmd, map_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::TransferDst);
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, layers_};
    device_->vkCmdClearDepthStencilImage(cmd, map_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &kFarPlane, 1, &range);
    gpu::transition(device_, cmd, map_, gpu::ImageState::TransferDst, gpu::ImageState::ShaderSampled);
}

void LayerStartPass::copy_cleared(VkCommandBuffer cmd) const {
    gpu::transition(device_, cmd, map_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::TransferDst);
    for (uint32_t layer = 0; layer < layers_; ++layer) {
        VkImageCopy region{};
        region.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
        region.dstSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, layer, 1};
        region.extent = {resolution_, resolution_, 1};
        device_->vkCmdCopyImage(cmd, source_.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, map_.get(),
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    }
    gpu::transition(device_, cmd, map_, gpu::ImageState::TransferDst, gpu::ImageState::ShaderSampled);
}

void LayerStartPass::record(VkCommandBuffer cmd, gpu::GpuTimer& timer) const {
    {
        gpu::TimedScope scope(timer, cmd, "start_render_pass_clear");
        render_pass_clear(cmd, resolution_);
    }
    {
        gpu::TimedScope scope(timer, cmd, "start_clear_image");
        clear_image(cmd);
    }
    {
        gpu::TimedScope scope(timer, cmd, "start_copy_cleared");
        copy_cleared(cmd);
    }
    gpu::TimedScope scope(timer, cmd, "start_clear_quarter");
    render_pass_clear(cmd, resolution_ / 2);  // a quarter of the texels
}

}  // namespace penumbra::bench
