#include "passes/moments_pass.hpp"

#include "embedded_shaders.hpp"
#include "gpu/barriers.hpp"
#include "passes/draw_recording.hpp"
#include "passes/shader_interface.hpp"
#include "passes/shadow_filter_specialization.hpp"

namespace penumbra::passes {
namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

gpu::Image create_layered(const gpu::Context& context, VkFormat format, uint32_t resolution, uint32_t layers,
                          VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    desc.usage = usage;
    desc.aspect = aspect;
    desc.array_view = true;
    return gpu::create_image(context, desc);
}

bool filters_linearly(const gpu::Context& context, VkFormat format) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), format, &properties);
    return (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
}

gpu::UniquePipeline create_caster_pipeline(const gpu::Context& context, VkPipelineLayout layout, VkFormat format,
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
    desc.depth_clamp = context.depth_clamp_supported();
    return gpu::create_graphics_pipeline(context, desc);
}

// Full-screen triangles (shaders/fullscreen.vert): the far-plane moments and the blur.
gpu::UniquePipeline create_fullscreen_pipeline(const gpu::Context& context, VkPipelineLayout layout,
                                               std::span<const uint32_t> fragment, VkFormat format,
                                               VkFormat depth_format, const FilterSettings& filter) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::fullscreen_vert(), {}});
    desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, fragment, shadow_filter_specialization(filter)});
    desc.layout = layout;
    desc.color_formats = {format};
    desc.depth_format = depth_format;
    desc.depth_compare = VK_COMPARE_OP_ALWAYS;
    desc.depth_write = false;
    desc.cull_mode = VK_CULL_MODE_NONE;
    return gpu::create_graphics_pipeline(context, desc);
}

VkRenderingAttachmentInfo attachment(VkImageView view, VkImageLayout layout, VkAttachmentLoadOp load) {
    VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    info.imageView = view;
    info.imageLayout = layout;
    info.loadOp = load;
    info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    return info;  // clear values are zero: reverse-Z far plane for depth
}

void begin_rendering(VkCommandBuffer cmd, uint32_t resolution, const VkRenderingAttachmentInfo& color,
                     const VkRenderingAttachmentInfo* depth) {
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {resolution, resolution}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    info.pDepthAttachment = depth;
    vkCmdBeginRendering(cmd, &info);
    set_viewport_and_scissor(cmd, resolution, resolution);
}

}  // namespace

VkFormat MomentsPass::moments_format(const FilterSettings& filter) {
    if (filter.mode == ShadowFilter::Msm) {
        return filter.msm_optimized_quantization ? VK_FORMAT_R16G16B16A16_UNORM : VK_FORMAT_R32G32B32A32_SFLOAT;
    }
    if (filter.mode == ShadowFilter::Evsm && filter.evsm_components == 4) return VK_FORMAT_R32G32B32A32_SFLOAT;
    return VK_FORMAT_R32G32_SFLOAT;
}

MomentsPass::MomentsPass(const gpu::Context& context, VkDescriptorSetLayout material_set_layout, uint32_t resolution,
                         uint32_t cascade_count, const FilterSettings& filter)
    : resolution_(resolution), cascade_count_(cascade_count), blur_radius_(static_cast<uint32_t>(filter.blur_radius)) {
    const VkFormat format = moments_format(filter);
    const VkImageUsageFlags color_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    moments_ = create_layered(context, format, resolution, cascade_count, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    if (blur_radius_ > 0) {
        scratch_ = create_layered(context, format, resolution, cascade_count, color_usage, VK_IMAGE_ASPECT_COLOR_BIT);
    }
    depth_ = create_layered(
        context, kDepthFormat, resolution, cascade_count,
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
        VK_IMAGE_ASPECT_DEPTH_BIT);

    gpu::SamplerDesc sampler;
    sampler.filter = filters_linearly(context, format) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_ = gpu::create_sampler(context, sampler);

    const VkDescriptorSetLayoutBinding frame_binding{PENUMBRA_BINDING_FRAME_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                                     1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                                     nullptr};
    frame_set_layout_ = gpu::create_descriptor_set_layout(context, {&frame_binding, 1});
    const VkDescriptorSetLayout caster_sets[] = {frame_set_layout_, material_set_layout};
    const VkPushConstantRange draw_range = draw_push_constant_range();
    caster_layout_ = gpu::create_pipeline_layout(context, caster_sets, {&draw_range, 1});
    casters_ = create_caster_pipeline(context, caster_layout_, format, filter);
    far_plane_ =
        create_fullscreen_pipeline(context, caster_layout_, shaders::moments_far_frag(), format, kDepthFormat, filter);

    if (blur_radius_ == 0) return;
    const VkDescriptorSetLayoutBinding source_binding{PENUMBRA_BINDING_BLUR_SOURCE,
                                                      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                                      VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    blur_set_layout_ = gpu::create_descriptor_set_layout(context, {&source_binding, 1});
    const VkPushConstantRange blur_range{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(shader::BlurPushConstants)};
    const VkDescriptorSetLayout blur_layout_sets[] = {blur_set_layout_};
    blur_layout_ = gpu::create_pipeline_layout(context, blur_layout_sets, {&blur_range, 1});
    blur_ = create_fullscreen_pipeline(context, blur_layout_, shaders::moments_blur_frag(), format, VK_FORMAT_UNDEFINED,
                                       filter);
    const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2};
    blur_pool_ = gpu::create_descriptor_pool(context, 2, {&pool_size, 1});
    const gpu::Image* sources[] = {&moments_, &scratch_};
    for (size_t i = 0; i < blur_sets_.size(); ++i) {
        blur_sets_[i] = gpu::allocate_descriptor_set(context, blur_pool_, blur_set_layout_);
        gpu::write_combined_image_sampler(context, blur_sets_[i], PENUMBRA_BINDING_BLUR_SOURCE, sources[i]->view,
                                          sampler_);
    }
}

void MomentsPass::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const DrawData& data,
                         const std::vector<std::vector<uint32_t>>& draw_lists) const {
    gpu::transition(cmd, moments_, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    gpu::transition(cmd, depth_, gpu::ImageState::Undefined, gpu::ImageState::DepthAttachment);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, caster_layout_, PENUMBRA_SET_FRAME, 1, &frame_set, 0,
                            nullptr);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &data.vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, data.index_buffer, 0, VK_INDEX_TYPE_UINT32);
    for (uint32_t cascade = 0; cascade < cascade_count_; ++cascade) {
        render_cascade(cmd, data, draw_lists[cascade], cascade);
    }
    gpu::transition(cmd, depth_, gpu::ImageState::DepthAttachment, gpu::ImageState::FragmentSampled);
    if (blur_radius_ > 0) blur(cmd);
    gpu::transition(cmd, moments_, gpu::ImageState::ColorAttachment, gpu::ImageState::FragmentSampled);
}

void MomentsPass::render_cascade(VkCommandBuffer cmd, const DrawData& data, const std::vector<uint32_t>& draws,
                                 uint32_t cascade) const {
    // The far-plane triangle covers every texel, so the colour needs no clear.
    const VkRenderingAttachmentInfo color = attachment(
        moments_.layer_views[cascade], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
    const VkRenderingAttachmentInfo depth =
        attachment(depth_.layer_views[cascade], VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_CLEAR);
    begin_rendering(cmd, resolution_, color, &depth);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, far_plane_);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    // One pipeline for opaque and alpha-masked casters: moments.frag alpha-tests by the
    // material's mode, since it runs for every caster anyway.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, casters_);
    for (const uint32_t index : draws) record_draw(cmd, caster_layout_, data, data.draws[index], cascade);
    vkCmdEndRendering(cmd);
}

void MomentsPass::blur(VkCommandBuffer cmd) const {
    gpu::transition(cmd, moments_, gpu::ImageState::ColorAttachment, gpu::ImageState::FragmentSampled);
    gpu::transition(cmd, scratch_, gpu::ImageState::Undefined, gpu::ImageState::ColorAttachment);
    blur_direction(cmd, blur_sets_[0], scratch_, true);
    gpu::transition(cmd, scratch_, gpu::ImageState::ColorAttachment, gpu::ImageState::FragmentSampled);
    gpu::transition(cmd, moments_, gpu::ImageState::FragmentSampled, gpu::ImageState::ColorAttachment);
    blur_direction(cmd, blur_sets_[1], moments_, false);
}

void MomentsPass::blur_direction(VkCommandBuffer cmd, VkDescriptorSet source, const gpu::Image& target,
                                 bool horizontal) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, blur_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, blur_layout_, 0, 1, &source, 0, nullptr);
    for (uint32_t layer = 0; layer < cascade_count_; ++layer) {
        const VkRenderingAttachmentInfo color = attachment(
            target.layer_views[layer], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
        begin_rendering(cmd, resolution_, color, nullptr);
        const shader::BlurPushConstants constants{{layer, blur_radius_, horizontal ? 1u : 0u, 0u}};
        vkCmdPushConstants(cmd, blur_layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
    }
}

}  // namespace penumbra::passes
