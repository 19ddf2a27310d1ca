#include "library/virtual_shadow_map.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/shadow_filters.hpp"
#include "library/conversions.hpp"
#include "passes/shader_interface.hpp"
#include "penumbra/errors.hpp"

namespace penumbra::library {
namespace {

// Pages of 128^2 D32 texels: 64 KiB each, 16 per MiB.
constexpr uint32_t kPagesPerMib = 16;

passes::VirtualPagesDesc pages_desc(const VirtualShadowSettings& settings, uint32_t frames_in_flight) {
    passes::VirtualPagesDesc desc;
    desc.level_count = static_cast<uint32_t>(settings.levels);
    desc.pages_per_side = settings.resolution / kVirtualPageTexels;
    desc.pool_pages = settings.pool_mib * kPagesPerMib;
    desc.max_page_draws = settings.page_draws;
    desc.frames_in_flight = frames_in_flight;
    return desc;
}

// The page draws' buffer must fit one storage buffer of the device.
passes::VirtualPagesDesc checked_pages_desc(const gpu::Device& device, const VirtualShadowSettings& settings,
                                            uint32_t frames_in_flight) {
    const uint64_t bytes = uint64_t{settings.page_draws} * sizeof(shader::VirtualPageDraw);
    const uint64_t range = device.properties().limits.maxStorageBufferRange;
    if (bytes > range) {
        throw DeviceError("Settings::shadow.virtual_maps.page_draws: " + std::to_string(settings.page_draws) +
                          " page draws take " + std::to_string(bytes) +
                          " bytes, more than one storage buffer of this device holds (maxStorageBufferRange " +
                          std::to_string(range) + ")");
    }
    return pages_desc(settings, frames_in_flight);
}

bool same_depth_mapping(const VirtualClipmap& a, const VirtualClipmap& b) {
    if (a.light_view != b.light_view || a.levels.size() != b.levels.size()) return false;
    for (size_t l = 0; l < a.levels.size(); ++l) {
        if (a.levels[l].depth_scale != b.levels[l].depth_scale ||
            a.levels[l].depth_offset != b.levels[l].depth_offset ||
            a.levels[l].texels_per_metre != b.levels[l].texels_per_metre) {
            return false;
        }
    }
    return true;
}

}  // namespace

VirtualClipmapConfig virtual_clipmap_config(const VirtualShadowSettings& settings) {
    VirtualClipmapConfig config;
    config.level_resolution = settings.resolution;
    config.level_count = static_cast<uint32_t>(settings.levels);
    config.first_level_extent = settings.first_level_extent;
    config.lod_bias = settings.lod_bias;
    return config;
}

float virtual_mark_radius_texels(const ShadowSettings& settings) {
    const FilterSettings& filter = settings.filter;
    float reach = 0.0f;  // beyond the bilinear tap's own texel
    switch (filter.mode) {
        case ShadowFilter::Pcf:
            reach = static_cast<float>(filter.pcf_radius);
            break;
        case ShadowFilter::Poisson:
            reach = filter.poisson_radius;
            break;
        case ShadowFilter::Pcss:
            reach = filter.pcss_max_penumbra;  // the search radius is clamped to it too
            break;
        default:
            break;
    }
    // The bilinear tap reads one texel further; one more for rounding at page edges.
    return settings.bias.normal_offset + reach + 2.0f;
}

VirtualShadowMap::VirtualShadowMap(const gpu::Device& device, VkDescriptorSetLayout caster_frame_layout,
                                   VkDescriptorSetLayout alpha_mask_layout, const ShadowSettings& settings,
                                   uint32_t frames_in_flight)
    : device_(device),
      config_(virtual_clipmap_config(settings.virtual_maps)),
      pages_(device, checked_pages_desc(device, settings.virtual_maps, frames_in_flight)),
      pass_(device, caster_frame_layout, alpha_mask_layout, pages_, frames_in_flight) {}

std::vector<shader::VirtualInvalidation> VirtualShadowMap::invalidations(const VirtualFrameInputs& inputs) const {
    // Static casters that changed (old and new bounds), and the dynamic casters where they
    // are now and where they were last frame: their pages are drawn again with everything
    // in them (static casters included), which keeps cached and uncached frames equal.
    std::vector<core::Aabb> boxes(inputs.static_changes.begin(), inputs.static_changes.end());
    boxes.insert(boxes.end(), dynamic_bounds_.begin(), dynamic_bounds_.end());
    for (const uint32_t draw : inputs.scene->dynamic_draws) boxes.push_back(inputs.scene->draws[draw].world_bounds);
    std::vector<shader::VirtualInvalidation> rects;
    const size_t per_level_limit = pages_.desc().max_invalidations / std::max<size_t>(clipmap_.levels.size(), 1);
    for (int level = 0; level < static_cast<int>(clipmap_.levels.size()); ++level) {
        std::vector<PageRect> level_rects;
        for (const core::Aabb& box : boxes) {
            const PageRect rect = world_pages_of_box(clipmap_, level, box);
            if (!rect.empty()) level_rects.push_back(rect);
        }
        // Too many for the GPU's list: their union, which covers them all.
        if (level_rects.size() > per_level_limit) {
            PageRect merged = level_rects.front();
            for (const PageRect& rect : level_rects) {
                merged.min = glm::min(merged.min, rect.min);
                merged.max = glm::max(merged.max, rect.max);
            }
            level_rects = {merged};
        }
        for (const PageRect& rect : level_rects) {
            rects.push_back({glm::ivec4(rect.min, rect.max), static_cast<uint32_t>(level), 0, 0, 0});
        }
    }
    return rects;
}

void VirtualShadowMap::prepare(const VirtualFrameInputs& inputs, const ShadowSettings& settings) {
    config_ = virtual_clipmap_config(settings.virtual_maps);
    clipmap_ = compute_virtual_clipmap(inputs.camera->eye, inputs.light_direction, config_, inputs.depth_range_bounds);
    // A new light direction, depth range or level size moves every texel: nothing cached
    // holds. Without the cache (Settings::shadow.cache_static_casters off) every page is
    // drawn every frame.
    const bool stale = invalidate_all_ || !previous_ || !same_depth_mapping(*previous_, clipmap_) ||
                       !settings.cache_static_casters || (inputs.casts && !casts_);
    std::vector<shader::VirtualInvalidation> rects =
        stale ? std::vector<shader::VirtualInvalidation>{} : invalidations(inputs);
    passes::VirtualFrameView view;
    view.camera_view = inputs.camera->view;
    view.camera_position = inputs.camera->eye;
    view.footprint_per_metre = inputs.footprint_per_metre;
    view.footprint_base = inputs.footprint_base;
    view.lod_bias = settings.virtual_maps.lod_bias;
    view.mark_radius_texels = virtual_mark_radius_texels(settings);
    view.shadow_distance = inputs.shadow_distance;
    view.frame = static_cast<uint32_t>(inputs.frame);
    shader::PenumbraVirtualClipmap block =
        passes::virtual_clipmap_block(clipmap_, previous_ ? *previous_ : clipmap_, view);
    block.invalidate_all = stale ? 1u : 0u;
    block.light_tan_half_angle = std::tan(glm::radians(inputs.sun_angular_diameter_degrees) * 0.5f);
    block.max_receiver_slope = kMaxReceiverSlope;
    block.fade_start = inputs.shadow_distance * (1.0f - settings.blend_width);
    // A sun that casts no shadow: no level, the shaders see the sun unshadowed.
    if (!inputs.casts) block.level_count = 0;
    if (inputs.scene->version != culled_version_) {
        cull_workgroups_ = passes::VirtualShadowPass::cull_workgroups(*inputs.scene);
        culled_version_ = inputs.scene->version;
    }
    pages_.prepare(inputs.frame, block, rects, cull_workgroups_);
    invalidation_count_ = static_cast<uint32_t>(rects.size());
    invalidated_all_ = stale;
    invalidate_all_ = false;
    casts_ = inputs.casts;
    previous_ = clipmap_;
    dynamic_bounds_.clear();
    for (const uint32_t draw : inputs.scene->dynamic_draws)
        dynamic_bounds_.push_back(inputs.scene->draws[draw].world_bounds);
}

void VirtualShadowMap::record_marking(VkCommandBuffer cmd, uint64_t frame, const ScreenInputs& screen,
                                      gpu::GpuTimer* timer) {
    shader::VirtualMarkPushConstants constants{};
    constants.inverse_view_projection = glm::inverse(to_glm(screen.view_projection));
    constants.width = screen.width;
    constants.height = screen.height;
    constants.background_depth = screen.background_depth;
    {
        gpu::TimedScope scope(device_, timer, cmd, "shadow_virtual_mark");
        pages_.record_marking(cmd, frame, screen.depth, screen.depth_layout, constants);
    }
    gpu::TimedScope scope(device_, timer, cmd, "shadow_virtual_allocate");
    pages_.record_allocation(cmd, frame);
}

void VirtualShadowMap::record_pages(VkCommandBuffer cmd, VkDescriptorSet caster_frame_set,
                                    const passes::CasterScene& scene, uint64_t frame, const BiasSettings& bias,
                                    const passes::CasterFaceCulling& culling, gpu::GpuTimer* timer) {
    pass_.record(cmd, caster_frame_set, scene, pages_, frame, bias, culling, timer);
}

VirtualShadowInfo VirtualShadowMap::info(uint64_t counted_frame) const {
    VirtualShadowInfo info;
    info.levels = casts_ ? static_cast<uint32_t>(clipmap_.levels.size()) : 0u;
    for (const VirtualLevel& level : clipmap_.levels) info.texel_world_size.push_back(level.texel_world_size);
    info.pool_pages = pages_.desc().pool_pages;
    info.pool_bytes = pass_.memory_bytes();
    info.invalidations = invalidation_count_;
    info.invalidated_all = invalidated_all_;
    if (counted_frame == 0) return info;
    if (const std::optional<shader::VirtualCounters> counters = pages_.counters(counted_frame)) {
        info.counted_frame = counted_frame;
        info.pages_requested = counters->requested;
        info.pages_rendered = counters->rendered;
        info.pages_cached = counters->cached;
        info.pages_unserved = counters->unserved;
        info.pages_resident = counters->resident;
        info.pages_evicted = counters->evicted;
        info.page_draws = counters->page_draws;
        info.dropped_page_draws = counters->dropped_page_draws;
        info.pages_deferred = counters->deferred;
    }
    if (const auto levels = pass_.culled(counted_frame)) {
        for (const passes::CulledLayer& level : *levels) info.page_draw_triangles += level.triangles;
    }
    return info;
}

}  // namespace penumbra::library
