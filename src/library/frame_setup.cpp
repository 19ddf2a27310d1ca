#include "library/frame_setup.hpp"

#include <array>
#include <cmath>

#include "core/caster_facing.hpp"
#include "core/shadow_filters.hpp"
#include "passes/shadow_filter_specialization.hpp"

namespace penumbra::library {
namespace {

VkFrontFace facing_light(const glm::mat4& view_projection) {
    return light_facing_is_counter_clockwise(view_projection) ? VK_FRONT_FACE_COUNTER_CLOCKWISE
                                                              : VK_FRONT_FACE_CLOCKWISE;
}

}  // namespace

std::vector<passes::LocalShadowLayer> cull_local_casters(std::span<const core::Light> lights,
                                                         const LocalShadowPlan& plan, const passes::CasterScene& scene,
                                                         bool cull, const std::vector<bool>& kept, bool gpu_culls) {
    std::vector<passes::LocalShadowLayer> layers;
    for (const LocalShadowSlot& slot : plan.slots) {
        const core::Light& light = lights[slot.light];
        const bool cube = local_shadow_is_cube(light);
        for (size_t face = 0; face < slot.view_projection.size(); ++face) {
            passes::LocalShadowLayer layer{slot.first_layer + static_cast<uint32_t>(face),
                                           slot.resolution,
                                           {},
                                           facing_light(slot.view_projection[face])};
            if (layer.layer < kept.size() && kept[layer.layer]) {
                layer.keep = true;
                layers.push_back(std::move(layer));
                continue;
            }
            // With culling, a cube face of a wide spot that its cone cannot reach stays cleared.
            if (cull && cube && !cube_face_reaches_cone(light, face)) {
                layers.push_back(std::move(layer));
                continue;
            }
            if (gpu_culls) {
                layer.gpu_culled = true;
                layers.push_back(std::move(layer));
                continue;
            }
            for (uint32_t d = 0; d < scene.draws.size(); ++d) {
                const core::Aabb& box = scene.draws[d].world_bounds;
                const bool may_cast = caster_may_shadow_frustum(slot.view_projection[face], box) &&
                                      (!cube || caster_may_shadow_sphere(light.position, light.range, box));
                if (!cull || may_cast) layer.draws.push_back(d);
            }
            layers.push_back(std::move(layer));
        }
    }
    return layers;
}

std::vector<core::Aabb> caster_bounds(const passes::CasterScene& scene) {
    std::vector<core::Aabb> boxes;
    boxes.reserve(scene.draws.size());
    for (const passes::CasterDraw& draw : scene.draws) boxes.push_back(draw.world_bounds);
    return boxes;
}

// The uniforms' copy of the filter's specialization constants, by constant id.
using FilterField = uint32_t shader::PenumbraShadowUniforms::*;
constexpr std::array<FilterField, PENUMBRA_SPEC_CONSTANT_COUNT> kFilterFields = [] {
    using U = shader::PenumbraShadowUniforms;
    std::array<FilterField, PENUMBRA_SPEC_CONSTANT_COUNT> fields{};
    fields[PENUMBRA_SPEC_FILTER_MODE] = &U::filter_mode;
    fields[PENUMBRA_SPEC_SEARCH_TAPS] = &U::filter_search_taps;
    fields[PENUMBRA_SPEC_FILTER_TAPS] = &U::filter_taps;
    fields[PENUMBRA_SPEC_RECEIVER_PLANE] = &U::filter_receiver_plane_bias;
    fields[PENUMBRA_SPEC_PCSS_EARLY_OUT] = &U::filter_pcss_early_out;
    fields[PENUMBRA_SPEC_MOMENTS_POISSON] = &U::filter_moments_poisson;
    fields[PENUMBRA_SPEC_EVSM_COMPONENTS] = &U::filter_evsm_components;
    fields[PENUMBRA_SPEC_MSM_QUANTIZED] = &U::filter_msm_quantized;
    return fields;
}();

shader::PenumbraShadowUniforms build_shadow_uniforms(const CameraView& camera, const CascadeSet& cascades,
                                                     const core::Light* sun, bool sun_casts_shadows,
                                                     const ShadowSettings& settings,
                                                     const passes::CasterDepthBias& caster_bias, uint32_t frame_index) {
    shader::PenumbraShadowUniforms uniforms{};
    uniforms.camera_view = camera.view;
    uniforms.camera_near = camera.near_plane;
    if (sun) uniforms.to_sun = glm::vec4(-glm::normalize(sun->direction), 1.0f);
    const float angular_diameter = sun ? sun->angular_diameter_degrees : 0.0f;
    for (size_t c = 0; c < cascades.cascades.size(); ++c) {
        const Cascade& cascade = cascades.cascades[c];
        const CascadeFilterParams params = cascade_filter_params(cascade, angular_diameter);
        shader::PenumbraCascade& out = uniforms.cascades[c];
        out.view_projection = cascade.view_projection;
        out.light_radius_uv_per_depth = params.light_radius_uv_per_depth;
        out.max_depth_gradient = params.max_depth_gradient;
        out.split_far = cascade.split_far;
        out.texel_world_size = cascade.texel_world_size;
        out.depth_scale = cascade.depth_scale;
        out.depth_offset = cascade.depth_offset;
        out.texels_per_metre = cascade.texels_per_metre;
        out.texel_origin = cascade.texel_origin;
        out.layer_origin = glm::vec2(cascade.layer_origin);
        uniforms.light_view = cascade.view;  // one light view for every cascade
    }
    uniforms.cascade_count = sun_casts_shadows ? static_cast<uint32_t>(cascades.cascades.size()) : 0u;
    uniforms.normal_offset_texels = settings.bias.normal_offset;
    uniforms.blend_width = settings.blend_width;
    uniforms.shadow_distance = cascades.shadow_distance;
    const FilterSettings& filter = settings.filter;
    uniforms.texel_uv = 1.0f / static_cast<float>(settings.cascades.resolution);
    uniforms.pcf_radius = static_cast<float>(filter.pcf_radius);
    uniforms.poisson_radius_texels = filter.poisson_radius;
    uniforms.pcss_max_penumbra_texels = filter.pcss_max_penumbra;
    uniforms.light_bleeding_reduction = filter.light_bleeding_reduction;
    const glm::vec2 exponents = clamped_evsm_exponents(filter);
    uniforms.evsm_positive_exponent = exponents.x;
    uniforms.evsm_negative_exponent = exponents.y;
    uniforms.msm_moment_bias = filter.msm_moment_bias;
    // VK_TRUE is 1: booleans read as != 0 either way.
    for (const gpu::SpecializationValue& value : passes::shadow_filter_specialization(filter)) {
        uniforms.*kFilterFields.at(value.constant_id) = value.value;
    }
    uniforms.frame_index = frame_index;
    uniforms.caster_slope_bias = caster_bias.slope;
    uniforms.caster_bias_clamp = caster_bias.clamp;
    return uniforms;
}

void set_contact_uniforms(shader::PenumbraShadowUniforms& uniforms, const ContactShadowSettings& contact) {
    uniforms.contact_lights = 0u;
    if (contact.enabled && contact.sun) uniforms.contact_lights |= PENUMBRA_CONTACT_SUN;
    if (contact.enabled && contact.local_lights) uniforms.contact_lights |= PENUMBRA_CONTACT_LOCAL;
    uniforms.contact_steps = static_cast<uint32_t>(contact.steps);
    uniforms.contact_length = contact.length;
    uniforms.contact_thickness = contact.thickness;
    uniforms.contact_bias = contact.bias;
    uniforms.contact_max_distance = contact.max_distance;
}

shader::PenumbraLocalShadows build_local_shadows(std::span<const core::Light> lights, const LocalShadowPlan& plan,
                                                 const ShadowSettings& settings,
                                                 const passes::CasterDepthBias& caster_bias) {
    shader::PenumbraLocalShadows uniforms{};
    uniforms.light_count = static_cast<uint32_t>(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const core::Light& light = lights[i];
        shader::PenumbraLocalShadow& out = uniforms.lights[i];
        out.position = light.position;
        out.range = light.range;
        out.first_layer = -1;
        out.cube = local_shadow_is_cube(light) ? 1u : 0u;
        out.uv_scale = 1.0f;
        out.radius = light.radius;
    }
    for (size_t s = 0; s < plan.slots.size(); ++s) {
        const LocalShadowSlot& slot = plan.slots[s];
        shader::PenumbraLocalShadow& out = uniforms.lights[slot.light];
        out.first_layer = static_cast<int32_t>(slot.first_layer);
        out.near_plane = slot.near_plane;
        out.fov_scale = 2.0f * std::tan(local_shadow_half_fov(lights[slot.light]));
        out.uv_scale = static_cast<float>(slot.resolution) / static_cast<float>(plan.atlas_resolution);
        for (size_t layer = 0; layer < slot.view_projection.size(); ++layer) {
            uniforms.layer_view_projection[slot.first_layer + layer] = slot.view_projection[layer];
        }
        uniforms.shadowed_lights[s / 4][static_cast<int>(s % 4)] = slot.light;
    }
    uniforms.shadowed_count = static_cast<uint32_t>(plan.slots.size());
    uniforms.normal_offset_texels = settings.bias.normal_offset;
    uniforms.texel_uv = plan.atlas_resolution > 0 ? 1.0f / static_cast<float>(plan.atlas_resolution) : 0.0f;
    uniforms.max_receiver_slope = kMaxReceiverSlope;
    uniforms.caster_slope_bias = caster_bias.slope;
    uniforms.caster_bias_clamp = caster_bias.clamp;
    return uniforms;
}

}  // namespace penumbra::library
