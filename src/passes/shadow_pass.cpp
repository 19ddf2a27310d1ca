#include "passes/shadow_pass.hpp"

#include <algorithm>
#include <string>

#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

void require_multiview(const gpu::Device& device, uint32_t cascade_count) {
    if (device.max_multiview_views() == 0) {
        throw DeviceError(
            "shadow strategy multiview: the device was not created with the multiview feature "
            "(VkPhysicalDeviceVulkan11Features::multiview)");
    }
    if (cascade_count > device.max_multiview_views()) {
        throw InputError("shadow strategy multiview: " + device.info().name + " renders at most " +
                         std::to_string(device.max_multiview_views()) + " views in one pass, not " +
                         std::to_string(cascade_count) + " cascades (use fewer cascades or per-cascade)");
    }
}

CasterPipelineTemplate depth_template(const gpu::Device& device, VkPipelineLayout layout, uint32_t view_mask) {
    CasterPipelineTemplate pipelines;
    const bool multiview = view_mask != 0;
    pipelines.opaque_vertex = multiview ? shaders::caster_multiview_vert() : shaders::caster_cascade_vert();
    pipelines.masked_vertex =
        multiview ? shaders::caster_multiview_masked_vert() : shaders::caster_cascade_masked_vert();
    pipelines.masked_fragment = shaders::caster_masked_frag();
    pipelines.layout = layout;
    pipelines.depth_bias = true;
    // Casters in front of a cascade's near plane are flattened onto it instead of clipped.
    pipelines.depth_clamp = device.depth_clamp_supported();
    pipelines.view_mask = view_mask;
    return pipelines;
}

gpu::UniquePipelineLayout create_caster_layout(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                               VkDescriptorSetLayout alpha_mask_set_layout) {
    const VkDescriptorSetLayout set_layouts[] = {frame_set_layout, alpha_mask_set_layout};
    const VkPushConstantRange push_range = caster_push_constant_range();
    return gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
}

}  // namespace

ShadowPass::ShadowPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                       VkDescriptorSetLayout alpha_mask_set_layout, uint32_t resolution, uint32_t cascade_count,
                       ShadowStrategy strategy)
    : device_(device),
      resolution_(resolution),
      cascade_count_(cascade_count),
      strategy_(strategy),
      shadow_map_(create_depth_map(device, resolution, cascade_count)),
      pipeline_layout_(create_caster_layout(device, frame_set_layout, alpha_mask_set_layout)),
      pipelines_(device, depth_template(device, pipeline_layout_,
                                        strategy == ShadowStrategy::Multiview ? (1u << cascade_count) - 1u : 0u)) {
    if (strategy == ShadowStrategy::Multiview) require_multiview(device, cascade_count);
}

void ShadowPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                        const std::vector<DrawList>& lists, const BiasSettings& bias, const CasterFaceCulling& culling,
                        gpu::GpuTimer* timer) const {
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::DiscardAfterShaderReads,
                    gpu::ImageState::DepthAttachment);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, PENUMBRA_SET_CASTER_FRAME,
                                     1, &frame_set, 0, nullptr);
    if (strategy_ == ShadowStrategy::Multiview) {
        // One pass renders every layer, so a draw goes in when any cascade needs it.
        DrawList union_list;
        for (const DrawList& list : lists) union_list.insert(union_list.end(), list.begin(), list.end());
        std::sort(union_list.begin(), union_list.end());
        union_list.erase(std::unique(union_list.begin(), union_list.end()), union_list.end());
        gpu::TimedScope scope(timer, cmd, "shadow_multiview");
        begin_rendering(cmd, shadow_map_.view, (1u << cascade_count_) - 1u, bias);
        record_caster_draws(device_, cmd, pipelines_, scene, union_list, 0, culling);
        device_->vkCmdEndRendering(cmd);
    } else {
        for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
            gpu::TimedScope scope(timer, cmd, "shadow_cascade_" + std::to_string(cascade));
            begin_rendering(cmd, shadow_map_.layer_views[cascade], 0, bias);
            record_caster_draws(device_, cmd, pipelines_, scene, lists[cascade], cascade, culling);
            device_->vkCmdEndRendering(cmd);
        }
    }
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::DepthAttachment, gpu::ImageState::ShaderSampled);
}

void ShadowPass::begin_rendering(VkCommandBuffer cmd, VkImageView view, uint32_t view_mask,
                                 const BiasSettings& bias) const {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: 0 is the far plane (no caster)
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {resolution_, resolution_}};
    info.layerCount = view_mask == 0 ? 1 : 0;
    info.viewMask = view_mask;
    info.pDepthAttachment = &depth;
    device_->vkCmdBeginRendering(cmd, &info);
    set_viewport_and_scissor(device_, cmd, resolution_, resolution_);
    set_shadow_depth_bias(device_, cmd, bias);
}

}  // namespace penumbra::passes
