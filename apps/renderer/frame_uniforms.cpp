#include "renderer/frame_uniforms.hpp"

#include <array>
#include <cmath>

#include "penumbra/gpu/pipeline.hpp"
#include "renderer/math_conversions.hpp"
#include "renderer/renderer.hpp"

namespace penumbra::renderer {
namespace {

const Light* first_directional(const std::vector<Light>& lights) {
    for (const Light& light : lights) {
        if (light.type == LightType::Directional) return &light;
    }
    return nullptr;
}

// The lit light written to the visibility target: its slot in LocalLights, or -1 (the sun).
int32_t visibility_slot(const std::vector<Light>& lights, int32_t visibility_light) {
    const std::vector<uint32_t> lit = lit_local_lights(lights);
    for (size_t slot = 0; slot < lit.size(); ++slot) {
        if (static_cast<int32_t>(lit[slot]) == visibility_light) return static_cast<int32_t>(slot);
    }
    return -1;
}

}  // namespace

gpu::UniqueDescriptorSetLayout create_frame_set_layout(const gpu::Device& device) {
    const std::array<VkDescriptorSetLayoutBinding, 4> bindings{{
        {RENDERER_BINDING_FRAME_UNIFORMS, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RENDERER_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RENDERER_BINDING_DRAW_MODELS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr},
        {RENDERER_BINDING_INSTANCE_DRAWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr},
    }};
    return gpu::create_descriptor_set_layout(device, bindings);
}

shader::FrameUniforms build_frame_uniforms(const ViewDesc& view, const Scene& scene, const RenderSettings& settings) {
    shader::FrameUniforms frame{};
    const glm::mat4 view_matrix = to_glm(view.view);
    frame.view_projection = to_glm(reverse_z_projection(view)) * view_matrix;
    frame.inverse_view_projection = glm::inverse(frame.view_projection);
    frame.screen = glm::vec4(static_cast<float>(settings.width), static_cast<float>(settings.height),
                             0.0f /* the pre-pass's reverse-Z far */, 0.0f);
    frame.camera_position = glm::vec4(glm::vec3(glm::inverse(view_matrix)[3]), 1.0f);
    if (const Light* sun = first_directional(scene.lights)) {
        frame.to_sun = glm::vec4(-glm::normalize(sun->direction), 1.0f);
        frame.sun_radiance = glm::vec4(sun->color * sun->intensity, 0.0f);
    }
    frame.ambient = glm::vec4(scene.ambient, 0.0f);
    frame.debug_view = settings.debug == DebugView::Cascades       ? RENDERER_DEBUG_VIEW_CASCADES
                       : settings.debug == DebugView::VirtualPages ? RENDERER_DEBUG_VIEW_VIRTUAL_PAGES
                                                                   : RENDERER_DEBUG_VIEW_NONE;
    frame.visibility_light = settings.visibility_light == kVisibilityContact
                                 ? RENDERER_VISIBILITY_CONTACT
                                 : visibility_slot(scene.lights, settings.visibility_light);
    frame.local_light_count = static_cast<uint32_t>(lit_local_lights(scene.lights).size());
    return frame;
}

shader::LocalLights build_local_lights(const std::vector<Light>& lights,
                                       const std::vector<LocalShadowInfo>& local_shadows) {
    shader::LocalLights result{};
    const std::vector<uint32_t> lit = lit_local_lights(lights);
    for (size_t slot = 0; slot < lit.size(); ++slot) {
        const Light& light = lights[lit[slot]];
        const bool spot = light.type == LightType::Spot;
        shader::LocalLight& out = result.lights[slot];
        out.position = light.position;
        out.range = light.range;
        out.direction = glm::normalize(light.direction);
        out.type = spot ? RENDERER_LIGHT_SPOT : RENDERER_LIGHT_POINT;
        out.radiance = light.color * light.intensity;
        out.cos_outer = spot ? std::cos(glm::radians(light.outer_angle_degrees)) : -1.0f;
        out.cos_inner = spot ? std::cos(glm::radians(light.inner_angle_degrees)) : -1.0f;
        out.shadow_index = lit[slot];
        for (const LocalShadowInfo& shadow : local_shadows) {
            if (shadow.light == lit[slot]) out.visibility_slot = shadow.slot;
        }
    }
    return result;
}

std::vector<LightDesc> shadow_lights(const std::vector<Light>& lights) {
    std::vector<LightDesc> result;
    result.reserve(lights.size());
    const std::vector<uint32_t> lit = lit_local_lights(lights);
    const uint32_t last_lit = lit.empty() ? 0 : lit.back();
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        LightDesc desc;
        desc.type = light.type;
        desc.direction = to_vec3(light.direction);
        desc.position = to_vec3(light.position);
        desc.angular_diameter_degrees = light.angular_diameter_degrees;
        desc.inner_angle_degrees = light.inner_angle_degrees;
        desc.outer_angle_degrees = light.outer_angle_degrees;
        desc.range = light.range;
        desc.radius = light.radius;
        desc.shadow_resolution = light.shadow_resolution;
        desc.cast_shadows = light.cast_shadows && (light.type == LightType::Directional || i <= last_lit);
        result.push_back(desc);
    }
    return result;
}

}  // namespace penumbra::renderer
