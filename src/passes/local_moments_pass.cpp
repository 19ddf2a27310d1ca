#include "passes/local_moments_pass.hpp"

#include "passes/shader_interface.hpp"
#include "penumbra/gpu/barriers.hpp"
#include "penumbra_shaders.hpp"

namespace penumbra::passes {

LocalMomentsPass::LocalMomentsPass(const gpu::Device& device, const gpu::Image& depth_map, VkSampler depth_sampler,
                                   const FilterSettings& filter)
    : device_(device),
      moments_(create_moments_image(device, moments_format(filter), depth_map.desc.width, depth_map.desc.layers)),
      sampler_(create_moments_sampler(device, moments_.desc.format)) {
    const VkDescriptorSetLayoutBinding source{PENUMBRA_BINDING_BLUR_SOURCE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                              1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    set_layout_ = gpu::create_descriptor_set_layout(device, {&source, 1});
    const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    pool_ = gpu::create_descriptor_pool(device, 1, {&pool_size, 1});
    depth_set_ = gpu::allocate_descriptor_set(device, pool_, set_layout_);
    gpu::write_combined_image_sampler(device, depth_set_, PENUMBRA_BINDING_BLUR_SOURCE, depth_map.view, depth_sampler);
    const VkPushConstantRange range{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(shader::LocalMomentsPushConstants)};
    const VkDescriptorSetLayout sets[] = {set_layout_};
    layout_ = gpu::create_pipeline_layout(device, sets, {&range, 1});
    convert_ = create_fullscreen_pipeline(device, layout_, shaders::local_moments_frag(), moments_.desc.format,
                                          VK_FORMAT_UNDEFINED, filter);
    if (filter.blur_radius > 0) {
        blur_.emplace(device, moments_, sampler_, static_cast<uint32_t>(filter.blur_radius), filter);
    }
}

uint64_t LocalMomentsPass::memory_bytes() const { return moments_.memory_size + (blur_ ? blur_->memory_bytes() : 0u); }

void LocalMomentsPass::record(VkCommandBuffer cmd, const std::vector<LocalMomentsLayer>& layers,
                              glm::vec2 evsm_exponents) const {
    gpu::transition(device_, cmd, moments_, gpu::ImageState::DiscardAfterShaderReads, gpu::ImageState::ColorAttachment);
    device_->vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, convert_);
    device_->vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &depth_set_, 0, nullptr);
    std::vector<BlurLayer> blur_layers;
    for (const LocalMomentsLayer& layer : layers) {
        const VkRenderingAttachmentInfo color =
            stored_attachment(moments_.layer_views[layer.layer], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                              VK_ATTACHMENT_LOAD_OP_DONT_CARE);
        begin_layer_rendering(device_, cmd, layer.resolution, color, nullptr);
        const shader::LocalMomentsPushConstants constants{
            {layer.layer, 0u, 0u, 0u}, {layer.near_plane, layer.far_plane, evsm_exponents.x, evsm_exponents.y}};
        device_->vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(constants), &constants);
        device_->vkCmdDraw(cmd, 3, 1, 0, 0);
        device_->vkCmdEndRendering(cmd);
        blur_layers.push_back({layer.layer, layer.resolution});
    }
    if (blur_) blur_->record(cmd, moments_, blur_layers);
    gpu::transition(device_, cmd, moments_, gpu::ImageState::ColorAttachment, gpu::ImageState::ShaderSampled);
}

}  // namespace penumbra::passes
