#include "renderer/local_light_setup.hpp"

#include <cmath>

#include "core/shadow_filters.hpp"

namespace penumbra::renderer {

static_assert(PENUMBRA_MAX_LOCAL_LIGHTS == kMaxLocalLights);
static_assert(PENUMBRA_MAX_LOCAL_SHADOW_LAYERS == kMaxLocalShadowLayers);

std::vector<Aabb> draw_bounds(const passes::DrawData& data) {
    std::vector<Aabb> boxes;
    boxes.reserve(data.draws.size());
    for (const passes::Draw& draw : data.draws) boxes.push_back(draw.world_bounds);
    return boxes;
}

namespace {

shader::LocalLight pack_light(const Light& light) {
    shader::LocalLight packed{};
    const bool spot = light.type == LightType::Spot;
    packed.position_range = glm::vec4(light.position, light.range);
    packed.direction_type =
        glm::vec4(glm::normalize(light.direction), spot ? PENUMBRA_LIGHT_SPOT : PENUMBRA_LIGHT_POINT);
    packed.radiance = glm::vec4(light.color * light.intensity, light.radius);
    const float cube_shadow = local_shadow_is_cube(light) ? 1.0f : 0.0f;
    packed.cone = spot ? glm::vec4(std::cos(glm::radians(light.outer_angle_degrees)),
                                   std::cos(glm::radians(light.inner_angle_degrees)), cube_shadow, 0.0f)
                       : glm::vec4(-1.0f, -1.0f, cube_shadow, 0.0f);
    packed.shadow = glm::vec4(-1.0f, 0.0f, 0.0f, 1.0f);
    return packed;
}

}  // namespace

shader::LocalLightUniforms build_local_light_uniforms(const Scene& scene, const LocalShadowPlan& plan,
                                                      const RenderSettings& settings) {
    shader::LocalLightUniforms uniforms{};
    int visibility_slot = -1;
    for (size_t slot = 0; slot < plan.local_lights.size(); ++slot) {
        const uint32_t index = plan.local_lights[slot];
        uniforms.lights[slot] = pack_light(scene.lights[index]);
        if (static_cast<int32_t>(index) == settings.visibility_light) visibility_slot = static_cast<int>(slot);
        for (const LocalShadowSlot& shadow : plan.slots) {
            if (shadow.light != index) continue;
            const float half_fov = local_shadow_half_fov(scene.lights[index]);
            uniforms.lights[slot].shadow =
                glm::vec4(static_cast<float>(shadow.first_layer), shadow.near_plane, 2.0f * std::tan(half_fov),
                          static_cast<float>(shadow.resolution) / static_cast<float>(plan.atlas_resolution));
            for (size_t layer = 0; layer < shadow.view_projection.size(); ++layer) {
                uniforms.shadow_view_projection[shadow.first_layer + layer] = shadow.view_projection[layer];
            }
        }
    }
    const float texel_uv = plan.atlas_resolution > 0 ? 1.0f / static_cast<float>(plan.atlas_resolution) : 0.0f;
    uniforms.counts = glm::vec4(static_cast<float>(plan.local_lights.size()), static_cast<float>(visibility_slot),
                                settings.shadow.bias.normal_offset, texel_uv);
    uniforms.filter_params = glm::vec4(static_cast<float>(settings.shadow.filter.pcf_radius),
                                       settings.shadow.filter.pcss_max_penumbra, kMaxReceiverSlope, 0.0f);
    return uniforms;
}

std::vector<passes::LocalShadowLayer> cull_local_casters(const Scene& scene, const LocalShadowPlan& plan,
                                                         const passes::DrawData& data, bool cull) {
    std::vector<passes::LocalShadowLayer> layers;
    for (const LocalShadowSlot& slot : plan.slots) {
        const Light& light = scene.lights[slot.light];
        const bool cube = local_shadow_is_cube(light);
        for (size_t face = 0; face < slot.view_projection.size(); ++face) {
            passes::LocalShadowLayer layer{slot.first_layer + static_cast<uint32_t>(face), slot.resolution, {}};
            // With culling, a cube face of a wide spot that its cone cannot reach stays cleared.
            if (cull && cube && !cube_face_reaches_cone(light, face)) {
                layers.push_back(std::move(layer));
                continue;
            }
            for (uint32_t d = 0; d < data.draws.size(); ++d) {
                const Aabb& box = data.draws[d].world_bounds;
                const bool may_cast = caster_may_shadow_frustum(slot.view_projection[face], box) &&
                                      (!cube || caster_may_shadow_sphere(light.position, light.range, box));
                if (!cull || may_cast) layer.draws.push_back(d);
            }
            layers.push_back(std::move(layer));
        }
    }
    return layers;
}

std::vector<LocalShadowStats> local_shadow_stats(const LocalShadowPlan& plan,
                                                 const std::vector<passes::LocalShadowLayer>& layers,
                                                 const passes::DrawData& data) {
    std::vector<LocalShadowStats> stats;
    for (const LocalShadowSlot& slot : plan.slots) {
        LocalShadowStats light{
            slot.light, static_cast<uint32_t>(slot.view_projection.size()), slot.resolution, slot.near_plane, 0, 0};
        for (const passes::LocalShadowLayer& layer : layers) {
            if (layer.layer < slot.first_layer || layer.layer >= slot.first_layer + light.layers) continue;
            light.draws += static_cast<uint32_t>(layer.draws.size());
            for (const uint32_t draw : layer.draws) light.triangles += data.draws[draw].index_count / 3;
        }
        stats.push_back(light);
    }
    return stats;
}

std::string local_shadow_budget_warning(const LocalShadowPlan& plan, const LocalShadowSettings& settings) {
    std::string warning;
    if (plan.over_budget > 0) {
        warning = "penumbra: warning: " + std::to_string(plan.over_budget) +
                  " shadow-casting spot/point light(s) beyond the local shadow budget of " +
                  std::to_string(settings.budget) + " render unshadowed (--local-shadow-budget)";
    }
    if (plan.beyond_light_limit > 0) {
        warning += (warning.empty() ? "penumbra: warning: " : "; ") + std::to_string(plan.beyond_light_limit) +
                   " spot/point light(s) beyond the first " + std::to_string(kMaxLocalLights) + " are not rendered";
    }
    return warning;
}

}  // namespace penumbra::renderer
