#include "passes/moments_pass.hpp"

#include "embedded_shaders.hpp"
#include "gpu/barriers.hpp"
#include "passes/draw_recording.hpp"
#include "passes/shader_interface.hpp"
#include "passes/shadow_filter_specialization.hpp"

namespace penumbra::passes {
namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

gpu::Image create_depth(const gpu::Device& device, uint32_t resolution, uint32_t layers) {
    gpu::ImageDesc desc;
    desc.format = kDepthFormat;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    desc.usage =
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    desc.array_view = true;
    return gpu::create_image(device, desc);
}

gpu::UniquePipeline create_caster_pipeline(const gpu::Device& device, VkPipelineLayout layout, VkFormat format,
                                           const FilterSettings& filter) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::shadow_depth_vert(), {}});
    desc.stages.push_back(
        {VK_SHADER_STAGE_FRAGMENT_BIT, shaders::moments_frag(), shadow_filter_specialization(filter)});
    desc.vertex_layout = scene_vertex_layout(VertexAttributes::PositionUv);
    desc.layout = layout;
    desc.color_formats = {format};
    desc.depth_format = kDepthFormat;
    desc.depth_compare = VK_COMPARE_OP_GREATER;  // reverse-Z: the caster nearest the light wins
    desc.cull_mode = VK_CULL_MODE_NONE;          // as in the depth pass: thin casters cast
    desc.depth_clamp = device.depth_clamp_supported();
    return gpu::create_graphics_pipeline(device, desc);
}

}  // namespace

MomentsPass::MomentsPass(const gpu::Device& device, VkDescriptorSetLayout material_set_layout, uint32_t resolution,
                         uint32_t cascade_count, const FilterSettings& filter)
    : device_(device),
      resolution_(resolution),
      cascade_count_(cascade_count),
      moments_(create_moments_image(device, moments_format(filter), resolution, cascade_count)),
      depth_(create_depth(device, resolution, cascade_count)),
      sampler_(create_moments_sampler(device, moments_.desc.format)) {
    const VkDescriptorSetLayoutBinding frame_binding{PENUMBRA_BINDING_FRAME_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                                     1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                                     nullptr};
    frame_set_layout_ = gpu::create_descriptor_set_layout(device, {&frame_binding, 1});
    const VkDescriptorSetLayout caster_sets[] = {frame_set_layout_, material_set_layout};
    const VkPushConstantRange draw_range = draw_push_constant_range();
    caster_layout_ = gpu::create_pipeline_layout(device, caster_sets, {&draw_range, 1});
    casters_ = create_caster_pipeline(device, caster_layout_, moments_.desc.format, filter);
    far_plane_ = create_fullscreen_pipeline(device, caster_layout_, shaders::moments_far_frag(), moments_.desc.format,
                                            kDepthFormat, filter);
    if (filter.blur_radius > 0) {
        blur_.emplace(device, moments_, sampler_, static_cast<uint32_t>(filter.blur_radius), filter);
    }
}

uint64_t MomentsPass::memory_bytes() const {
    return moments_.memory_size + depth_.memory_size + (blur_ ? blur_->memory_bytes() : 0u);
}

void MomentsPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data,
                         const std::vector<std::vector<uint32_t>>& draw_lists) const {
    gpu::transition(device_, cmd, moments_, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    gpu::transition(device_, cmd, depth_, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, caster_layout_, PENUMBRA_SET_FRAME, 1,
                                     &frame_set, 0, nullptr);
    VkDeviceSize offset = 0;
    device_->vkCmdBindVertexBuffers(cmd, 0, 1, &data.vertex_buffer, &offset);
    device_->vkCmdBindIndexBuffer(cmd, data.index_buffer, 0, VK_INDEX_TYPE_UINT32);
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        render_cascade(cmd, data, draw_lists[cascade], cascade);
    }
    gpu::transition(device_, cmd, depth_, gpu::ImageState::DepthAttachment, gpu::ImageState::FragmentSampled);
    // A cascade without casters holds the far plane's moments in every texel, and a blur
    // leaves a uniform layer as it is: only cascades with casters are blurred.
    std::vector<BlurLayer> blurred;
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        if (!draw_lists[cascade].empty()) blurred.push_back({cascade, resolution_});
    }
    if (blur_ && !blurred.empty()) blur_->record(cmd, moments_, blurred);
    gpu::transition(device_, cmd, moments_, gpu::ImageState::ColorAttachment, gpu::ImageState::FragmentSampled);
}

void MomentsPass::render_cascade(VkCommandBuffer cmd, const DrawData& data, const std::vector<uint32_t>& draws,
                                 uint32_t cascade) const {
    // The far-plane triangle covers every texel, so the colour needs no clear.
    const VkRenderingAttachmentInfo color = stored_attachment(
        moments_.layer_views[cascade], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
    const VkRenderingAttachmentInfo depth = stored_attachment(
        depth_.layer_views[cascade], VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_CLEAR);
    begin_layer_rendering(device_, cmd, resolution_, color, &depth);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, far_plane_);
    device_->vkCmdDraw(cmd, 3, 1, 0, 0);
    // One pipeline for opaque and alpha-masked casters: moments.frag alpha-tests by the
    // material's mode, since it runs for every caster anyway.
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, casters_);
    for (const uint32_t index : draws) record_draw(device_, cmd, caster_layout_, data, data.draws[index], cascade);
    device_->vkCmdEndRendering(cmd);
}

}  // namespace penumbra::passes
