#pragma once
// The C++ side of penumbra/shadow_interface.h (the caller-facing descriptor set) and of
// shaders/include/penumbra_internal.h (the passes' push constants): the same structs,
// checked member by member against their std140/std430 offsets so that C++ and GLSL
// cannot disagree, and the limits checked against the library's C++ constants.
#include <cstddef>
#include <cstdint>
#include <iterator>

#include "core/glm_config.hpp"
#include "core/virtual_clipmap.hpp"
#include "penumbra/settings.hpp"
#include "penumbra/shadow_system.hpp"

namespace penumbra::shader {

using mat4 = glm::mat4;
using vec4 = glm::vec4;
using vec3 = glm::vec3;
using vec2 = glm::vec2;
using uvec4 = glm::uvec4;
using ivec2 = glm::ivec2;
using ivec4 = glm::ivec4;

#include "penumbra_internal.h"

static_assert(sizeof(mat4) == 64 && sizeof(vec4) == 16 && sizeof(vec3) == 12 && sizeof(vec2) == 8);

static_assert(PENUMBRA_MAX_CASCADES == kMaxCascades);
static_assert(PENUMBRA_MAX_PCF_RADIUS == kMaxPcfRadius);
// ResolvePushConstants::normal_encoding is the enum's value.
static_assert(static_cast<int>(NormalEncoding::SignedFloat) == 0 &&
              static_cast<int>(NormalEncoding::UnsignedNormalized) == 1 &&
              static_cast<int>(NormalEncoding::Octahedral) == 2);
// The filter specialization constant is the ShadowFilter's value: the enum is dense and
// listed in order by its choice table, which has one entry per GLSL filter id.
static_assert(PENUMBRA_FILTER_COUNT == std::size(kShadowFilterChoices));
static_assert([] {
    for (size_t i = 0; i < std::size(kShadowFilterChoices); ++i) {
        if (static_cast<size_t>(kShadowFilterChoices[i].value) != i) return false;
    }
    return true;
}());
static_assert(PENUMBRA_FILTER_HARD == static_cast<uint32_t>(ShadowFilter::Hard) &&
              PENUMBRA_FILTER_PCF == static_cast<uint32_t>(ShadowFilter::Pcf) &&
              PENUMBRA_FILTER_POISSON == static_cast<uint32_t>(ShadowFilter::Poisson) &&
              PENUMBRA_FILTER_PCSS == static_cast<uint32_t>(ShadowFilter::Pcss) &&
              PENUMBRA_FILTER_VSM == static_cast<uint32_t>(ShadowFilter::Vsm) &&
              PENUMBRA_FILTER_EVSM == static_cast<uint32_t>(ShadowFilter::Evsm) &&
              PENUMBRA_FILTER_MSM == static_cast<uint32_t>(ShadowFilter::Msm));
static_assert(PENUMBRA_MAX_LIGHTS == kMaxLights);
static_assert(PENUMBRA_MAX_LOCAL_SHADOW_LAYERS == kMaxLocalShadowLayers);
static_assert(PENUMBRA_MAX_SHADOWED_LIGHTS == kMaxLocalShadowBudget);

static_assert(offsetof(PenumbraCascade, light_radius_uv_per_depth) == 64);
static_assert(offsetof(PenumbraCascade, max_depth_gradient) == 72);
static_assert(offsetof(PenumbraCascade, split_far) == 80);
static_assert(offsetof(PenumbraCascade, texel_world_size) == 84);
static_assert(offsetof(PenumbraCascade, depth_scale) == 88);
static_assert(offsetof(PenumbraCascade, texels_per_metre) == 96);
static_assert(offsetof(PenumbraCascade, texel_origin) == 104);
static_assert(offsetof(PenumbraCascade, layer_origin) == 112);
static_assert(sizeof(PenumbraCascade) == 128);

static_assert(offsetof(PenumbraShadowUniforms, light_view) == 64);
static_assert(offsetof(PenumbraShadowUniforms, cascades) == 128);
static_assert(offsetof(PenumbraShadowUniforms, to_sun) == 128 + 128 * PENUMBRA_MAX_CASCADES);
static_assert(offsetof(PenumbraShadowUniforms, cascade_count) == offsetof(PenumbraShadowUniforms, to_sun) + 16);
static_assert(offsetof(PenumbraShadowUniforms, camera_near) == offsetof(PenumbraShadowUniforms, cascade_count) + 16);
static_assert(offsetof(PenumbraShadowUniforms, light_bleeding_reduction) ==
              offsetof(PenumbraShadowUniforms, camera_near) + 20);
static_assert(offsetof(PenumbraShadowUniforms, frame_index) ==
              offsetof(PenumbraShadowUniforms, light_bleeding_reduction) + 16);
static_assert(offsetof(PenumbraShadowUniforms, caster_slope_bias) == offsetof(PenumbraShadowUniforms, frame_index) + 4);
static_assert(offsetof(PenumbraShadowUniforms, caster_bias_clamp) == offsetof(PenumbraShadowUniforms, frame_index) + 8);
static_assert(offsetof(PenumbraShadowUniforms, contact_lights) == offsetof(PenumbraShadowUniforms, frame_index) + 12);
static_assert(offsetof(PenumbraShadowUniforms, contact_length) == offsetof(PenumbraShadowUniforms, contact_lights) + 8);
static_assert(offsetof(PenumbraShadowUniforms, contact_max_distance) ==
              offsetof(PenumbraShadowUniforms, contact_lights) + 20);
static_assert(offsetof(PenumbraShadowUniforms, filter_mode) == offsetof(PenumbraShadowUniforms, contact_lights) + 32);
static_assert(offsetof(PenumbraShadowUniforms, filter_msm_quantized) ==
              offsetof(PenumbraShadowUniforms, filter_mode) + 4 * (PENUMBRA_SPEC_CONSTANT_COUNT - 1));
static_assert(sizeof(PenumbraShadowUniforms) == offsetof(PenumbraShadowUniforms, filter_mode) + 32);
static_assert(sizeof(PenumbraShadowUniforms) % 16 == 0);
static_assert(sizeof(PenumbraShadowUniforms) <= 16384, "Vulkan guarantees 16 KiB uniform buffer ranges");

static_assert(offsetof(CullInstance, bounds_min) == 64);
static_assert(offsetof(CullInstance, bounds_max) == 80);
static_assert(offsetof(CullInstance, bucket) == 96);
static_assert(offsetof(CullInstance, vertex_offset) == 108);
static_assert(sizeof(CullInstance) == 112);
static_assert(sizeof(CullRecord) == 8);
static_assert(offsetof(CullPushConstants, first_dynamic_bucket) == 20);
static_assert(offsetof(CullPushConstants, resolution) == 24);
static_assert(offsetof(CullPushConstants, layer_mask) == 32);
static_assert(offsetof(CullTile, rects) == 16);
static_assert(sizeof(CullTile) == 32);
static_assert(sizeof(CullPushConstants) == 64);
static_assert(PENUMBRA_MAX_LOCAL_SHADOW_LAYERS <= 8 * sizeof(CullPushConstants::layer_mask));

static_assert(offsetof(PenumbraLocalShadow, range) == 12);
static_assert(offsetof(PenumbraLocalShadow, first_layer) == 16);
static_assert(offsetof(PenumbraLocalShadow, uv_scale) == 32);
static_assert(sizeof(PenumbraLocalShadow) == 48);

static_assert(offsetof(PenumbraLocalShadows, shadowed_count) == 16);
static_assert(offsetof(PenumbraLocalShadows, caster_slope_bias) == 20);
static_assert(offsetof(PenumbraLocalShadows, caster_bias_clamp) == 24);
static_assert(offsetof(PenumbraLocalShadows, shadowed_lights) == 32);
static_assert(offsetof(PenumbraLocalShadows, layer_view_projection) == 32 + 16 * (PENUMBRA_MAX_SHADOWED_LIGHTS / 4));
static_assert(offsetof(PenumbraLocalShadows, lights) ==
              offsetof(PenumbraLocalShadows, layer_view_projection) + 64 * PENUMBRA_MAX_LOCAL_SHADOW_LAYERS);
static_assert(sizeof(PenumbraLocalShadows) ==
              offsetof(PenumbraLocalShadows, lights) + sizeof(PenumbraLocalShadow) * PENUMBRA_MAX_LIGHTS);

static_assert(offsetof(CasterPushConstants, layer) == 64);
static_assert(offsetof(CasterPushConstants, alpha_scale) == 72);
static_assert(offsetof(CasterPushConstants, tile) == 76);
static_assert(sizeof(CasterPushConstants) == 80);
static_assert(offsetof(MomentsPushConstants, depth_range) == 16);
static_assert(offsetof(MomentsPushConstants, window) == 32);
static_assert(offsetof(MomentsPushConstants, region) == 48);
static_assert(sizeof(MomentsPushConstants) == 64);
static_assert(offsetof(ResolvePushConstants, width) == 64);
static_assert(offsetof(ResolvePushConstants, background_depth) == 80);
static_assert(offsetof(ResolvePushConstants, has_face_normals) == 88);
static_assert(sizeof(ResolvePushConstants) == 96);
static_assert(sizeof(ResolvePushConstants) <= 128, "Vulkan guarantees only 128 bytes of push constants");

static_assert(PENUMBRA_MAX_VIRTUAL_LEVELS == kMaxVirtualLevels);
static_assert(offsetof(PenumbraVirtualLevel, previous_first_page) == 8);
static_assert(offsetof(PenumbraVirtualLevel, texels_per_metre) == 16);
static_assert(offsetof(PenumbraVirtualLevel, depth_offset) == 28);
static_assert(sizeof(PenumbraVirtualLevel) == 32);
static_assert(offsetof(PenumbraVirtualClipmap, camera_view) == 64);
static_assert(offsetof(PenumbraVirtualClipmap, camera_position) == 128);
static_assert(offsetof(PenumbraVirtualClipmap, level_count) == 144);
static_assert(offsetof(PenumbraVirtualClipmap, lod_scale) == 160);
static_assert(offsetof(PenumbraVirtualClipmap, invalidation_count) == 176);
static_assert(offsetof(PenumbraVirtualClipmap, light_tan_half_angle) == 188);
static_assert(offsetof(PenumbraVirtualClipmap, fade_start) == 196);
static_assert(offsetof(PenumbraVirtualClipmap, footprint_base) == 200);
static_assert(offsetof(PenumbraVirtualClipmap, levels) == 208);
static_assert(sizeof(PenumbraVirtualClipmap) == 208 + 32 * PENUMBRA_MAX_VIRTUAL_LEVELS);
static_assert(sizeof(PenumbraVirtualClipmap) <= 16384, "Vulkan guarantees 16 KiB uniform buffer ranges");
static_assert(offsetof(VirtualInvalidation, level) == 16);
static_assert(sizeof(VirtualInvalidation) == 32);
static_assert(sizeof(VirtualPhysicalPage) == 8);
static_assert(offsetof(VirtualCounters, threshold_bucket) == 32);
static_assert(sizeof(VirtualDispatch) == sizeof(VkDispatchIndirectCommand));
static_assert(offsetof(VirtualCounters, assign_groups) == 48);
static_assert(offsetof(VirtualCounters, cull_groups) == 60);
static_assert(offsetof(VirtualCounters, scan_groups_done) == 72);
static_assert(offsetof(VirtualCounters, deferred) == 80);
static_assert(offsetof(VirtualCounters, level_needs) == 96);
static_assert(offsetof(VirtualCounters, age_histogram) == 96 + 4 * PENUMBRA_MAX_VIRTUAL_LEVELS);
static_assert(sizeof(VirtualClearDraw) == sizeof(VkDrawIndirectCommand));
static_assert(offsetof(VirtualClearDraw, instance_count) == offsetof(VkDrawIndirectCommand, instanceCount));
static_assert(offsetof(VirtualClearDraw, first_instance) == offsetof(VkDrawIndirectCommand, firstInstance));
static_assert(offsetof(VirtualCounters, level_clears) ==
              96 + 4 * (PENUMBRA_MAX_VIRTUAL_LEVELS + PENUMBRA_VIRTUAL_AGE_BUCKETS));
static_assert(offsetof(VirtualCounters, render_budget) ==
              96 + 4 * (PENUMBRA_MAX_VIRTUAL_LEVELS + PENUMBRA_VIRTUAL_AGE_BUCKETS) + 16 * PENUMBRA_MAX_VIRTUAL_LEVELS);
static_assert(offsetof(VirtualCounters, page_draws) == offsetof(VirtualCounters, render_budget) + 8);
static_assert(sizeof(VirtualCounters) == offsetof(VirtualCounters, render_budget) + 16);
static_assert(sizeof(VirtualPageDraw) == 8);
static_assert(sizeof(VirtualCullPushConstants) == 16);
static_assert(offsetof(VirtualMarkPushConstants, width) == 64);
static_assert(offsetof(VirtualMarkPushConstants, background_depth) == 72);
static_assert(sizeof(VirtualMarkPushConstants) == 80);
static_assert(sizeof(VirtualStepPushConstants) == 32);

}  // namespace penumbra::shader
