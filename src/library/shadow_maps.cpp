#include "library/shadow_maps.hpp"

#include <algorithm>

#include "core/shadow_filters.hpp"
#include "penumbra/gpu/debug_names.hpp"

namespace penumbra::library {
namespace {

// The map is at least 16 x 16 with one layer, so the descriptor set always binds a valid image.
constexpr uint32_t kPlaceholderResolution = 16;

gpu::UniqueSampler create_nearest_sampler(const gpu::Device& device) {
    gpu::SamplerDesc sampler;
    sampler.filter = VK_FILTER_NEAREST;
    sampler.address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    return gpu::create_sampler(device, sampler);
}

// The moment filters store each texel's occluder distance itself: their variance, not a
// depth offset, keeps receivers from shadowing themselves.
BiasSettings depth_bias_of(const ShadowSettings& settings) {
    if (!is_moment_filter(settings.filter.mode)) return settings.bias;
    BiasSettings none = settings.bias;
    none.constant = 0.0f;
    none.slope = 0.0f;
    return none;
}

}  // namespace

// Every filter renders the cascades' depth; the moment filters convert it to moments.
CascadeMaps::CascadeMaps(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                         VkDescriptorSetLayout alpha_mask_set_layout, const ShadowSettings& settings,
                         uint32_t frames_in_flight)
    : device_(device),
      depth_pass_(device, frame_set_layout, alpha_mask_set_layout, settings.cascades.resolution,
                  static_cast<uint32_t>(settings.cascades.count), settings.strategy, settings.cache_static_casters,
                  frames_in_flight),
      depth_sampler_(create_nearest_sampler(device)) {
    if (is_moment_filter(settings.filter.mode)) {
        // Cached cascades update their moments only where the depth changed.
        moments_.emplace(device, depth_pass_.shadow_map(), depth_sampler_, settings.filter, depth_pass_.cached());
    }
}

void CascadeMaps::prepare_pipelines(const passes::VertexFormats& formats) { depth_pass_.prepare_pipelines(formats); }

SampledMaps CascadeMaps::sampled() const {
    if (moments_) return {&depth_pass_.shadow_map(), &moments_->moments(), moments_->sampler()};
    return {&depth_pass_.shadow_map(), nullptr, VK_NULL_HANDLE};
}

uint64_t CascadeMaps::memory_bytes() const {
    return depth_pass_.memory_bytes() + (moments_ ? moments_->memory_bytes() : 0u);
}

void CascadeMaps::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const passes::CasterScene& scene,
                         const std::vector<passes::CascadeDraws>& draws, const ShadowSettings& settings,
                         const passes::CasterFaceCulling& culling, bool sun_casts, uint64_t frame,
                         gpu::GpuTimer* timer) {
    const passes::GpuCullOptions gpu_culling{sun_casts, settings.cull_casters, frame};
    depth_pass_.record(cmd, frame_set, scene, draws, depth_bias_of(settings), culling, timer, gpu_culling);
    if (!moments_) return;
    gpu::TimedScope scope(device_, timer, cmd, "shadow_moments");
    const gpu::ImageDesc& map = depth_pass_.shadow_map().desc;
    std::vector<passes::MomentsLayer> layers;
    for (uint32_t cascade = 0; cascade < map.layers; ++cascade) {
        const passes::CascadeDraws& drawn = draws[cascade];
        passes::MomentsLayer layer{cascade, map.width, 0.0f, 0.0f, glm::uvec2(drawn.layer_origin)};  // orthographic
        if (drawn.reuse && moments_->partial_updates()) layer.changed = drawn.changed;
        layers.push_back(std::move(layer));
    }
    moments_->record(cmd, layers, clamped_evsm_exponents(settings.filter));
}

LocalMaps::LocalMaps(const gpu::Device& device, VkDescriptorSetLayout frame_set_layout,
                     VkDescriptorSetLayout alpha_mask_set_layout, const ShadowSettings& settings,
                     RetiredObjects& retired, uint32_t frames_in_flight)
    : device_(device),
      filter_(settings.filter),
      retired_(retired),
      pass_(device, frame_set_layout, alpha_mask_set_layout, settings.strategy == ShadowStrategy::Layered,
            frames_in_flight),
      depth_sampler_(create_nearest_sampler(device)) {
    map_ = std::make_unique<gpu::Image>(passes::create_depth_map(device, kPlaceholderResolution, 1));
}

void LocalMaps::fit(const LocalShadowPlan& plan, uint64_t frame) {
    const uint32_t layers = plan.layer_count;
    const uint32_t resolution = layers > 0 ? plan.atlas_resolution : 0u;
    if (layers == layers_ && resolution == resolution_) return;
    const gpu::ObjectNames names(device_, "local light maps");
    retired_.retire(std::move(map_), frame);
    retired_.retire(std::move(moments_), frame);
    layers_ = layers;
    resolution_ = resolution;
    placeholder_ready_ = false;
    ++generation_;
    map_ = std::make_unique<gpu::Image>(
        passes::create_depth_map(device_, std::max(resolution, kPlaceholderResolution), std::max(layers, 1u)));
    if (is_moment_filter(filter_.mode) && layers > 0) {
        moments_ = std::make_unique<passes::MomentsConversion>(device_, *map_, depth_sampler_, filter_);
    }
}

SampledMaps LocalMaps::sampled() const {
    if (moments_) return {map_.get(), &moments_->moments(), moments_->sampler()};
    return {map_.get(), nullptr, VK_NULL_HANDLE};
}

uint64_t LocalMaps::memory_bytes() const {
    if (layers_ == 0) return 0;  // the 16 x 16 placeholder is not counted
    return map_->memory_size + (moments_ ? moments_->memory_bytes() : 0u);
}

void LocalMaps::record(VkCommandBuffer cmd, VkDescriptorSet frame_set, const passes::CasterScene& scene,
                       const std::vector<passes::LocalShadowLayer>& layers, const LocalShadowPlan& plan,
                       const ShadowSettings& settings, uint64_t frame, gpu::GpuTimer* timer) {
    if (layers_ == 0) {
        // Nothing samples the placeholder map, but the descriptor set binds it in this
        // layout: cleared once, then left as it is.
        if (!placeholder_ready_) gpu::record_depth_clear_to_sampled(device_, cmd, *map_, 0.0f);  // reverse-Z: far
        placeholder_ready_ = true;
        return;
    }
    gpu::TimedScope scope(device_, timer, cmd, "shadow_local");
    pass_.record(cmd, frame_set, scene, layers, *map_, settings.bias, settings.caster_culling, settings.cull_casters,
                 frame);
    if (!moments_) return;
    // Kept layers keep their moments too.
    std::vector<bool> kept(layers_, false);
    for (const passes::LocalShadowLayer& layer : layers) kept[layer.layer] = layer.keep;
    std::vector<passes::MomentsLayer> moments_layers;
    for (const LocalShadowSlot& slot : plan.slots) {
        for (uint32_t face = 0; face < slot.view_projection.size(); ++face) {
            if (kept[slot.first_layer + face]) continue;
            moments_layers.push_back({slot.first_layer + face, slot.resolution, slot.near_plane, slot.far_plane});
        }
    }
    const bool keep_others = std::find(kept.begin(), kept.end(), true) != kept.end();
    moments_->record(cmd, moments_layers, clamped_evsm_exponents(settings.filter), keep_others);
}

}  // namespace penumbra::library
