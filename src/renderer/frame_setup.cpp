#include "renderer/frame_setup.hpp"

#include "renderer/filter_uniforms.hpp"

namespace penumbra::renderer {

glm::vec3 sun_travel_direction(const Scene& scene) {
    const Light* sun = scene.sun();
    return sun ? glm::normalize(sun->direction) : glm::vec3(0.0f, -1.0f, 0.0f);
}

bool sun_casts_shadows(const Scene& scene) {
    const Light* sun = scene.sun();
    return sun && sun->cast_shadows;
}

CulledCasters cull_casters(const Scene& scene, const CascadeSet& cascades, const passes::DrawData& data, bool cull) {
    CulledCasters result;
    result.lists.resize(cascades.cascades.size());
    result.stats.resize(cascades.cascades.size());
    if (!sun_casts_shadows(scene)) return result;
    for (size_t c = 0; c < cascades.cascades.size(); ++c) {
        for (uint32_t d = 0; d < data.draws.size(); ++d) {
            const passes::Draw& draw = data.draws[d];
            if (cull && !caster_may_shadow_cascade(cascades.cascades[c], draw.world_bounds)) continue;
            result.lists[c].push_back(d);
            result.stats[c].draws += 1;
            result.stats[c].triangles += draw.index_count / 3;
        }
    }
    return result;
}

shader::FrameUniforms build_frame_uniforms(const CameraView& camera, const Scene& scene, const CascadeSet& cascades,
                                           const RenderSettings& settings, uint32_t frame_index) {
    shader::FrameUniforms frame{};
    frame.view_projection = camera.view_projection;
    frame.view = camera.view;
    frame.camera_position = glm::vec4(camera.eye, 1.0f);
    frame.camera_params = glm::vec4(camera.near_plane, camera.far_plane, 0.0f, 0.0f);
    frame.ambient = glm::vec4(scene.ambient, 0.0f);

    const Light* sun = scene.sun();
    const bool shadowed = sun_casts_shadows(scene);
    if (sun) {
        frame.sun_direction = glm::vec4(-glm::normalize(sun->direction), 1.0f);
        frame.sun_radiance = glm::vec4(sun->color * sun->intensity, shadowed ? 1.0f : 0.0f);
    }
    const auto count = static_cast<int>(cascades.cascades.size());
    for (int c = 0; c < count; ++c) {
        const Cascade& cascade = cascades.cascades[c];
        frame.cascade_view_projection[c] = cascade.view_projection;
        frame.cascade_split_far[c / 4][c % 4] = cascade.split_far;
        frame.cascade_texel_world_size[c / 4][c % 4] = cascade.texel_world_size;
    }
    frame.shadow_params = glm::vec4(shadowed ? static_cast<float>(count) : 0.0f, settings.shadow.bias.normal_offset,
                                    settings.shadow.blend_width, cascades.shadow_distance);
    frame.options = glm::uvec4(
        settings.debug == DebugView::Cascades ? PENUMBRA_DEBUG_VIEW_CASCADES : PENUMBRA_DEBUG_VIEW_NONE, 0u, 0u, 0u);
    fill_filter_uniforms(frame, scene, cascades, settings.shadow, frame_index);
    return frame;
}

}  // namespace penumbra::renderer
