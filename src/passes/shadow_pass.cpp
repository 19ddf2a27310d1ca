#include "passes/shadow_pass.hpp"

#include <algorithm>
#include <string>

#include "embedded_shaders.hpp"
#include "gpu/barriers.hpp"
#include "passes/draw_recording.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"

namespace penumbra::passes {
namespace {

constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;

gpu::UniquePipeline create_shadow_pipeline(const gpu::Device& device, VkPipelineLayout layout, bool masked,
                                           uint32_t view_mask) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::shadow_depth_vert(), {}});
    if (masked) desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, shaders::shadow_masked_frag(), {}});
    desc.vertex_layout = scene_vertex_layout(VertexAttributes::PositionUv);
    desc.layout = layout;
    desc.depth_format = kShadowFormat;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z: the caster nearest the light wins
    // Casters are not culled: thin and single-sided geometry (planes, leaves) must still cast,
    // and the slope-scaled bias handles the acne that back-face culling would otherwise hide.
    desc.cull_mode = VK_CULL_MODE_NONE;
    desc.depth_bias = true;
    // Casters in front of a cascade's near plane are flattened onto it instead of clipped.
    desc.depth_clamp = device.depth_clamp_supported();
    desc.view_mask = view_mask;
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

ShadowPass::ShadowPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout, uint32_t resolution,
                       uint32_t cascade_count, ShadowStrategy strategy)
    : device_(device), resolution_(resolution), cascade_count_(cascade_count), strategy_(strategy) {
    if (strategy == ShadowStrategy::Multiview && cascade_count > device.max_multiview_views()) {
        throw InputError("--shadow-strategy multiview: " + device.info().name + " renders at most " +
                         std::to_string(device.max_multiview_views()) + " views in one pass, not " +
                         std::to_string(cascade_count) + " cascades (use fewer cascades or per-cascade)");
    }
    gpu::ImageDesc desc;
    desc.format = kShadowFormat;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = cascade_count;
    desc.usage =
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    desc.array_view = true;
    shadow_map_ = gpu::create_image(device, desc);

    const VkDescriptorSetLayoutBinding frame_binding{PENUMBRA_BINDING_FRAME_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                                     1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
    frame_set_layout_ = gpu::create_descriptor_set_layout(device, {&frame_binding, 1});
    const VkDescriptorSetLayout set_layouts[] = {frame_set_layout_, material_set_layout};
    const VkPushConstantRange push_range = draw_push_constant_range();
    pipeline_layout_ = gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});

    if (strategy == ShadowStrategy::Multiview) {
        const uint32_t all_cascades = (1u << cascade_count) - 1u;
        opaque_multiview_ = create_shadow_pipeline(device, pipeline_layout_, false, all_cascades);
        masked_multiview_ = create_shadow_pipeline(device, pipeline_layout_, true, all_cascades);
    } else {
        opaque_per_cascade_ = create_shadow_pipeline(device, pipeline_layout_, false, 0);
        masked_per_cascade_ = create_shadow_pipeline(device, pipeline_layout_, true, 0);
    }
}

void ShadowPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data,
                        const std::vector<CascadeDrawList>& draw_lists, const BiasSettings& bias,
                        gpu::GpuTimer* timer) const {
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, PENUMBRA_SET_FRAME, 1,
                                     &frame_set, 0, nullptr);
    VkDeviceSize offset = 0;
    device_->vkCmdBindVertexBuffers(cmd, 0, 1, &data.vertex_buffer, &offset);
    device_->vkCmdBindIndexBuffer(cmd, data.index_buffer, 0, VK_INDEX_TYPE_UINT32);
    if (strategy_ == ShadowStrategy::Multiview) {
        record_multiview(cmd, data, draw_lists, bias, timer);
    } else {
        record_per_cascade(cmd, data, draw_lists, bias, timer);
    }
    gpu::transition(device_, cmd, shadow_map_, gpu::ImageState::DepthAttachment, gpu::ImageState::FragmentSampled);
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
    // Reverse-Z: pushing a caster away from the light lowers its depth, so every bias term
    // is negative (a negative clamp bounds the bias from below). Without the depthBiasClamp
    // feature the bias is unclamped.
    const float clamp = device_.depth_bias_clamp_supported() ? -bias.clamp : 0.0f;
    device_->vkCmdSetDepthBias(cmd, -bias.constant, clamp, -bias.slope);
}

void ShadowPass::record_per_cascade(VkCommandBuffer cmd, const DrawData& data,
                                    const std::vector<CascadeDrawList>& lists, const BiasSettings& bias,
                                    gpu::GpuTimer* timer) const {
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        gpu::TimedScope scope(timer, cmd, "shadow_cascade_" + std::to_string(cascade));
        begin_rendering(cmd, shadow_map_.layer_views[cascade], 0, bias);
        record_draws(cmd, data, lists[cascade], cascade, opaque_per_cascade_, masked_per_cascade_);
        device_->vkCmdEndRendering(cmd);
    }
}

void ShadowPass::record_multiview(VkCommandBuffer cmd, const DrawData& data, const std::vector<CascadeDrawList>& lists,
                                  const BiasSettings& bias, gpu::GpuTimer* timer) const {
    // One pass renders every layer, so a draw goes in when any cascade needs it.
    CascadeDrawList union_list;
    for (const CascadeDrawList& list : lists) union_list.insert(union_list.end(), list.begin(), list.end());
    std::sort(union_list.begin(), union_list.end());
    union_list.erase(std::unique(union_list.begin(), union_list.end()), union_list.end());

    gpu::TimedScope scope(timer, cmd, "shadow_multiview");
    begin_rendering(cmd, shadow_map_.view, (1u << cascade_count_) - 1u, bias);
    record_draws(cmd, data, union_list, 0, opaque_multiview_, masked_multiview_);
    device_->vkCmdEndRendering(cmd);
}

void ShadowPass::record_draws(VkCommandBuffer cmd, const DrawData& data, const CascadeDrawList& list, uint32_t cascade,
                              VkPipeline opaque, VkPipeline masked) const {
    // Opaque casters first, then masked ones, so each pipeline is bound once.
    for (const bool masked_pass : {false, true}) {
        device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, masked_pass ? masked : opaque);
        for (uint32_t index : list) {
            const Draw& draw = data.draws[index];
            if (data.materials[draw.material].alpha_masked != masked_pass) continue;
            record_draw(device_, cmd, pipeline_layout_, data, draw, cascade);
        }
    }
}

}  // namespace penumbra::passes
