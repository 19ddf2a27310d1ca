#include "renderer/shadow_filter_resources.hpp"

#include "core/shadow_filters.hpp"
#include "passes/shader_interface.hpp"

namespace penumbra::renderer {

ShadowFilterResources::ShadowFilterResources(const gpu::Context& context, VkDescriptorSetLayout material_set_layout,
                                             const RenderSettings& settings, VkBuffer frame_uniforms,
                                             VkDeviceSize frame_uniforms_size)
    : context_(context) {
    // Raw depth for the blocker search: point sampling, so a blocker's depth is a real
    // caster depth rather than a blend with the background.
    gpu::SamplerDesc sampler;
    sampler.filter = VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    depth_sampler_ = gpu::create_sampler(context, sampler);

    const FilterSettings& filter = settings.shadow.filter;
    if (!is_moment_filter(filter.mode)) return;
    moments_pass_.emplace(context, material_set_layout, settings.shadow.cascades.resolution,
                          static_cast<uint32_t>(settings.shadow.cascades.count), filter);
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
    pool_ = gpu::create_descriptor_pool(context, 1, {&size, 1});
    moments_frame_set_ = gpu::allocate_descriptor_set(context, pool_, moments_pass_->frame_set_layout());
    gpu::write_uniform_buffer(context, moments_frame_set_, PENUMBRA_BINDING_FRAME_UNIFORMS, frame_uniforms,
                              frame_uniforms_size);
}

const gpu::Image& ShadowFilterResources::depth_map(const gpu::Image& depth_pass_map) const {
    return moments_pass_ ? moments_pass_->depth() : depth_pass_map;
}

void ShadowFilterResources::write_lighting_bindings(VkDescriptorSet lighting_set, const gpu::Image& depth_pass_map,
                                                    VkSampler comparison_sampler) const {
    const gpu::Image& depth = depth_map(depth_pass_map);
    gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_SHADOW_MAP, depth.view,
                                      comparison_sampler);
    gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_SHADOW_DEPTH, depth.view,
                                      depth_sampler_);
    if (moments_pass_) {
        gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_SHADOW_MOMENTS,
                                          moments_pass_->moments().view, moments_pass_->moments_sampler());
    } else {
        // Not read by the comparison filters, but every binding must hold a valid image.
        gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_SHADOW_MOMENTS, depth.view,
                                          depth_sampler_);
    }
}

void ShadowFilterResources::record_moments(VkCommandBuffer cmd, const passes::DrawData& data,
                                           const std::vector<std::vector<uint32_t>>& draw_lists) const {
    moments_pass_->record(cmd, moments_frame_set_, data, draw_lists);
}

uint64_t ShadowFilterResources::memory_bytes() const {
    if (!moments_pass_) return 0;
    return moments_pass_->memory_bytes();
}

}  // namespace penumbra::renderer
