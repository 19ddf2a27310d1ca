#include "renderer/local_shadow_resources.hpp"

#include <algorithm>
#include <cstring>

#include "core/shadow_filters.hpp"
#include "passes/shader_interface.hpp"
#include "renderer/local_light_setup.hpp"

namespace penumbra::renderer {
namespace {

// The map is at least 16 x 16 with one layer, so the lighting set always binds a valid image.
constexpr uint32_t kPlaceholderResolution = 16;

gpu::UniqueSampler create_raw_depth_sampler(const gpu::Context& context) {
    gpu::SamplerDesc sampler;
    sampler.filter = VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    return gpu::create_sampler(context, sampler);
}

}  // namespace

LocalShadowResources::LocalShadowResources(const gpu::Context& context, const Scene& scene,
                                           const RenderSettings& settings, VkDescriptorSetLayout material_set_layout)
    : context_(context),
      plan_(plan_local_shadows(scene, settings.local_shadows)),
      shadow_pass_(context, material_set_layout, std::max(plan_.atlas_resolution, kPlaceholderResolution),
                   plan_.layer_count),
      uniforms_(gpu::create_buffer(context, sizeof(shader::LocalLightUniforms), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   gpu::MemoryKind::HostUpload)),
      depth_sampler_(create_raw_depth_sampler(context)) {
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    pool_ = gpu::create_descriptor_pool(context, 1, {&size, 1});
    shadow_set_ = gpu::allocate_descriptor_set(context, pool_, shadow_pass_.set_layout());
    gpu::write_storage_buffer(context, shadow_set_, 0, uniforms_.get(), sizeof(shader::LocalLightUniforms));
    if (is_moment_filter(settings.shadow.filter.mode) && plan_.layer_count > 0) {
        moments_pass_.emplace(context, shadow_pass_.shadow_map(), depth_sampler_, settings.shadow.filter);
    }
}

void LocalShadowResources::write_lighting_bindings(VkDescriptorSet lighting_set, VkSampler comparison_sampler) const {
    gpu::write_storage_buffer(context_, lighting_set, PENUMBRA_BINDING_LOCAL_LIGHTS, uniforms_.get(),
                              sizeof(shader::LocalLightUniforms));
    const VkImageView map = shadow_pass_.shadow_map().view;
    gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_LOCAL_SHADOW_MAP, map,
                                      comparison_sampler);
    gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_LOCAL_SHADOW_DEPTH, map, depth_sampler_);
    if (moments_pass_) {
        gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_LOCAL_MOMENTS,
                                          moments_pass_->moments().view, moments_pass_->sampler());
    } else {
        // Not read by the comparison filters, but every binding must hold a valid image.
        gpu::write_combined_image_sampler(context_, lighting_set, PENUMBRA_BINDING_LOCAL_MOMENTS, map, depth_sampler_);
    }
}

std::vector<LocalShadowStats> LocalShadowResources::prepare(const Scene& scene, const passes::DrawData& data,
                                                            const RenderSettings& settings, const CameraView& camera) {
    fit_local_shadows(plan_, scene, draw_bounds(data));
    size_local_shadows(plan_, scene, camera, settings.height, settings.local_shadows.resolution);
    const shader::LocalLightUniforms uniforms = build_local_light_uniforms(scene, plan_, settings);
    std::memcpy(uniforms_.mapped, &uniforms, sizeof(uniforms));
    layers_ = cull_local_casters(scene, plan_, data, settings.shadow.cull_casters);
    return local_shadow_stats(plan_, layers_, data);
}

void LocalShadowResources::record(VkCommandBuffer cmd, const passes::DrawData& data, const RenderSettings& settings,
                                  gpu::GpuTimer* timer) const {
    if (plan_.layer_count == 0) {
        // Nothing samples the placeholder map, but the lighting set binds it in this layout.
        shadow_pass_.record_placeholder(cmd);
        return;
    }
    gpu::TimedScope scope(timer, cmd, "shadow_local");
    shadow_pass_.record(cmd, shadow_set_, data, layers_, settings.shadow.bias);
    if (!moments_pass_) return;
    std::vector<passes::LocalMomentsLayer> moments_layers;
    for (const LocalShadowSlot& slot : plan_.slots) {
        for (uint32_t face = 0; face < slot.view_projection.size(); ++face) {
            moments_layers.push_back({slot.first_layer + face, slot.resolution, slot.near_plane, slot.far_plane});
        }
    }
    moments_pass_->record(cmd, moments_layers, clamped_evsm_exponents(settings.shadow.filter));
}

uint64_t LocalShadowResources::memory_bytes() const {
    if (plan_.layer_count == 0) return 0;  // the 16 x 16 placeholder is not counted
    return shadow_pass_.shadow_map().memory_size + (moments_pass_ ? moments_pass_->memory_bytes() : 0u);
}

std::string LocalShadowResources::budget_warning(const LocalShadowSettings& settings) const {
    return local_shadow_budget_warning(plan_, settings);
}

}  // namespace penumbra::renderer
