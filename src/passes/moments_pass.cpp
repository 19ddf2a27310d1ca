#include "passes/moments_pass.hpp"

#include "passes/shader_interface.hpp"
#include "passes/shadow_filter_specialization.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

gpu::UniquePipelineLayout create_caster_layout(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                                               VkDescriptorSetLayout alpha_mask_set_layout) {
    const VkDescriptorSetLayout set_layouts[] = {frame_set_layout, alpha_mask_set_layout};
    const VkPushConstantRange push_range = caster_push_constant_range();
    return gpu::create_pipeline_layout(device, set_layouts, {&push_range, 1});
}

CasterPipelineTemplate moments_template(const gpu::Device& device, VkPipelineLayout layout, VkFormat format,
                                        const FilterSettings& filter) {
    CasterPipelineTemplate pipelines;
    pipelines.opaque_vertex = shaders::caster_cascade_vert();
    pipelines.masked_vertex = shaders::caster_cascade_masked_vert();
    pipelines.opaque_fragment = shaders::moments_frag();
    pipelines.masked_fragment = shaders::moments_masked_frag();
    pipelines.fragment_specialization = shadow_filter_specialization(filter);
    pipelines.layout = layout;
    pipelines.color_formats = {format};
    pipelines.depth_format = kDepthFormat;
    pipelines.depth_clamp = device.depth_clamp_supported();
    return pipelines;
}

}  // namespace

MomentsPass::MomentsPass(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                         VkDescriptorSetLayout alpha_mask_set_layout, uint32_t resolution, uint32_t cascade_count,
                         const FilterSettings& filter)
    : device_(device),
      resolution_(resolution),
      cascade_count_(cascade_count),
      moments_(create_moments_image(device, moments_format(filter), resolution, cascade_count)),
      depth_(create_depth_map(device, resolution, cascade_count)),
      sampler_(create_moments_sampler(device, moments_.desc.format)),
      caster_layout_(create_caster_layout(device, frame_set_layout, alpha_mask_set_layout)),
      far_plane_(create_fullscreen_pipeline(device, caster_layout_, shaders::moments_far_frag(), moments_.desc.format,
                                            kDepthFormat, filter)),
      casters_(device, moments_template(device, caster_layout_, moments_.desc.format, filter)) {
    if (filter.blur_radius > 0) {
        blur_.emplace(device, moments_, sampler_, static_cast<uint32_t>(filter.blur_radius), filter);
    }
}

uint64_t MomentsPass::memory_bytes() const {
    return moments_.memory_size + depth_.memory_size + (blur_ ? blur_->memory_bytes() : 0u);
}

void MomentsPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const CasterScene& scene,
                         const std::vector<DrawList>& lists, const CasterFaceCulling& culling) const {
    gpu::transition(device_, cmd, moments_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::ColorAttachment);
    gpu::transition(device_, cmd, depth_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::DepthAttachment);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, caster_layout_, PENUMBRA_SET_CASTER_FRAME, 1,
                                     &frame_set, 0, nullptr);
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        render_cascade(cmd, scene, lists[cascade], cascade, culling);
    }
    gpu::transition(device_, cmd, depth_, gpu::ImageState::DepthAttachment, gpu::ImageState::ShaderSampled);
    // A cascade without casters holds the far plane's moments in every texel, and a blur
    // leaves a uniform layer as it is: only cascades with casters are blurred.
    std::vector<BlurLayer> blurred;
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        if (!lists[cascade].empty()) blurred.push_back({cascade, resolution_});
    }
    if (blur_ && !blurred.empty()) blur_->record(cmd, moments_, blurred);
    gpu::transition(device_, cmd, moments_, gpu::ImageState::ColorAttachment, gpu::ImageState::ShaderSampled);
}

void MomentsPass::render_cascade(VkCommandBuffer cmd, const CasterScene& scene, const DrawList& draws, uint32_t cascade,
                                 const CasterFaceCulling& culling) const {
    // The far-plane triangle covers every texel, so the colour needs no clear.
    const VkRenderingAttachmentInfo color = stored_attachment(
        moments_.layer_views[cascade], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
    const VkRenderingAttachmentInfo depth = stored_attachment(
        depth_.layer_views[cascade], VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_CLEAR);
    begin_layer_rendering(device_, cmd, resolution_, color, &depth);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, far_plane_);
    device_->vkCmdDraw(cmd, 3, 1, 0, 0);
    record_caster_draws(device_, cmd, casters_, scene, draws, cascade, culling);
    device_->vkCmdEndRendering(cmd);
}

}  // namespace penumbra::passes
