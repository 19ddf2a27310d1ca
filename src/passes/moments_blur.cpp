#include "passes/moments_blur.hpp"

#include "passes/casters.hpp"
#include "passes/shader_interface.hpp"
#include "passes/shadow_filter_specialization.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {
namespace {

bool filters_linearly(const gpu::Device& device, VkFormat format) {
    VkFormatProperties properties{};
    device->vkGetPhysicalDeviceFormatProperties(device.physical_device(), format, &properties);
    return (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
}

}  // namespace

VkFormat moments_format(const FilterSettings& filter) {
    if (filter.mode == ShadowFilter::Msm) {
        return filter.msm_optimized_quantization ? VK_FORMAT_R16G16B16A16_UNORM : VK_FORMAT_R32G32B32A32_SFLOAT;
    }
    if (filter.mode == ShadowFilter::Evsm && filter.evsm_components == 4) return VK_FORMAT_R32G32B32A32_SFLOAT;
    return VK_FORMAT_R32G32_SFLOAT;
}

gpu::Image create_moments_image(const gpu::Device& device, VkFormat format, uint32_t resolution, uint32_t layers) {
    gpu::ImageDesc desc;
    desc.format = format;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    desc.array_view = true;
    return gpu::create_image(device, desc);
}

gpu::UniqueSampler create_moments_sampler(const gpu::Device& device, VkFormat format) {
    gpu::SamplerDesc sampler;
    sampler.filter = filters_linearly(device, format) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    return gpu::create_sampler(device, sampler);
}

gpu::UniquePipeline create_fullscreen_pipeline(const gpu::Device& device, VkPipelineLayout layout,
                                               std::span<const uint32_t> fragment, VkFormat color_format,
                                               VkFormat depth_format, const FilterSettings& filter) {
    gpu::GraphicsPipelineDesc desc;
    desc.stages.push_back({VK_SHADER_STAGE_VERTEX_BIT, shaders::fullscreen_vert(), {}});
    desc.stages.push_back({VK_SHADER_STAGE_FRAGMENT_BIT, fragment, shadow_filter_specialization(filter)});
    desc.layout = layout;
    desc.color_formats = {color_format};
    desc.depth_format = depth_format;
    desc.depth_compare = VK_COMPARE_OP_ALWAYS;
    desc.depth_write = false;
    desc.cull_mode = VK_CULL_MODE_NONE;
    return gpu::create_graphics_pipeline(device, desc);
}

VkRenderingAttachmentInfo stored_attachment(VkImageView view, VkImageLayout layout, VkAttachmentLoadOp load) {
    VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    info.imageView = view;
    info.imageLayout = layout;
    info.loadOp = load;
    info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    return info;
}

void begin_layer_rendering(const gpu::Device& device, VkCommandBuffer cmd, uint32_t resolution,
                           const VkRenderingAttachmentInfo& color, const VkRenderingAttachmentInfo* depth) {
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {resolution, resolution}};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    info.pDepthAttachment = depth;
    device->vkCmdBeginRendering(cmd, &info);
    set_viewport_and_scissor(device, cmd, resolution, resolution);
}

MomentsBlur::MomentsBlur(const gpu::Device& device, const gpu::Image& moments, VkSampler sampler, uint32_t radius,
                         const FilterSettings& filter)
    : device_(device),
      radius_(radius),
      scratch_(create_moments_image(device, moments.desc.format, moments.desc.width, moments.desc.layers)) {
    const VkDescriptorSetLayoutBinding source_binding{PENUMBRA_BINDING_BLUR_SOURCE,
                                                      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                                      VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    set_layout_ = gpu::create_descriptor_set_layout(device, {&source_binding, 1});
    const VkPushConstantRange range{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(shader::BlurPushConstants)};
    const VkDescriptorSetLayout sets[] = {set_layout_};
    layout_ = gpu::create_pipeline_layout(device, sets, {&range, 1});
    pipeline_ = create_fullscreen_pipeline(device, layout_, shaders::moments_blur_frag(), moments.desc.format,
                                           VK_FORMAT_UNDEFINED, filter);
    const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2};
    pool_ = gpu::create_descriptor_pool(device, 2, {&pool_size, 1});
    const VkImageView sources[] = {moments.view, scratch_.view};
    for (size_t i = 0; i < sets_.size(); ++i) {
        sets_[i] = gpu::allocate_descriptor_set(device, pool_, set_layout_);
        gpu::write_combined_image_sampler(device, sets_[i], PENUMBRA_BINDING_BLUR_SOURCE, sources[i], sampler);
    }
}

void MomentsBlur::record(VkCommandBuffer cmd, const gpu::Image& moments, const std::vector<BlurLayer>& layers) const {
    gpu::transition(device_, cmd, moments, gpu::ImageState::ColorAttachment, gpu::ImageState::FragmentSampled);
    gpu::transition(device_, cmd, scratch_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::ColorAttachment);
    blur_direction(cmd, sets_[0], scratch_, layers, true);
    gpu::transition(device_, cmd, scratch_, gpu::ImageState::ColorAttachment, gpu::ImageState::FragmentSampled);
    gpu::transition(device_, cmd, moments, gpu::ImageState::FragmentSampled, gpu::ImageState::ColorAttachment);
    blur_direction(cmd, sets_[1], moments, layers, false);
}

void MomentsBlur::blur_direction(VkCommandBuffer cmd, VkDescriptorSet source, const gpu::Image& target,
                                 const std::vector<BlurLayer>& layers, bool horizontal) const {
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &source, 0, nullptr);
    for (const BlurLayer& layer : layers) {
        const VkRenderingAttachmentInfo color = stored_attachment(
            target.layer_views[layer.layer], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_LOAD_OP_DONT_CARE);
        begin_layer_rendering(device_, cmd, layer.resolution, color, nullptr);
        const shader::BlurPushConstants constants{{layer.layer, radius_, horizontal ? 1u : 0u, layer.resolution}};
        device_->vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
        device_->vkCmdDraw(cmd, 3, 1, 0, 0);
        device_->vkCmdEndRendering(cmd);
    }
}

}  // namespace penumbra::passes
