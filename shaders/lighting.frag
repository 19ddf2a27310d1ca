#version 460
// Forward shading of the sun (Lambert diffuse + GGX specular) and ambient, with the
// sun's visibility from the cascaded shadow map. Besides the tone-mapped colour it
// writes two exact outputs used by tests and tools: the sun's visibility (R16_UNORM)
// and the index of the cascade that shadowed the pixel (R8_UINT).
#extension GL_GOOGLE_include_directive : require
#include "penumbra_shared.h"

layout(std140, set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};
layout(push_constant) uniform PushBlock { DrawPushConstants draw; };
layout(set = PENUMBRA_SET_MATERIAL, binding = PENUMBRA_BINDING_BASE_COLOR_TEXTURE) uniform sampler2D base_color_texture;

#include "shadow.glsl"
#include "shading.glsl"
#include "local_lights.glsl"

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec4 out_color;
layout(location = 1) out float out_visibility;
layout(location = 2) out uint out_cascade;

const vec3 kCascadeTints[8] = vec3[](vec3(1.0, 0.25, 0.25), vec3(0.25, 1.0, 0.25), vec3(0.3, 0.45, 1.0),
                                     vec3(1.0, 1.0, 0.25), vec3(1.0, 0.3, 1.0), vec3(0.25, 1.0, 1.0),
                                     vec3(1.0, 0.6, 0.2), vec3(0.7, 0.7, 0.7));

// The receiver's geometric plane (receiver-plane bias of the local lights): the cross
// product of the position's screen-space derivatives, or the shading normal where the
// triangle is too small or too oblique for them.
vec3 geometric_normal(vec3 position, vec3 shading_normal) {
    const vec3 n = cross(dFdx(position), dFdy(position));
    const float length_squared = dot(n, n);
    return length_squared > 1e-20 ? n * inversesqrt(length_squared) : shading_normal;
}

void main() {
    vec3 normal = normalize(in_world_normal);
    if (!gl_FrontFacing) normal = -normal;  // double-sided materials are lit from both sides
    const float view_depth = -(frame.view * vec4(in_world_position, 1.0)).z;
    const bool sun_casts_shadows = frame.sun_radiance.w != 0.0 && cascade_count() > 0;
    const int cascade = sun_casts_shadows ? select_cascade(view_depth) : -1;
    // Before the discard and every per-pixel branch: they take screen-space derivatives.
    const ShadowReceiver receiver = prepare_shadow_receiver(cascade, in_world_position, normal);
    const vec3 plane_normal = geometric_normal(in_world_position, normal);

    vec4 base_color = draw.base_color;
    if (draw.flags.y != 0u) base_color *= texture(base_color_texture, in_uv);
    if (draw.flags.z == PENUMBRA_ALPHA_MASK && base_color.a < draw.material.x) discard;

    const vec3 to_sun = frame.sun_direction.xyz;
    const float n_dot_l = dot(normal, to_sun);
    float visibility = 1.0;
    if (frame.sun_direction.w == 0.0 || n_dot_l <= 0.0) {
        visibility = 0.0;  // no sun, or the surface faces away from it
    } else if (cascade >= 0) {
        visibility = sun_visibility(cascade, receiver, view_depth);
    }

    vec3 color = shade_sun(base_color.rgb, normal, normalize(frame.camera_position.xyz - in_world_position), to_sun,
                           frame.sun_radiance.rgb * visibility, draw.material.y, draw.material.z);
    // Spot and point lights; with `--aov shadow:N` light N's visibility (shadow, cone, range,
    // facing) replaces the sun's in the visibility target.
    const vec3 to_view = normalize(frame.camera_position.xyz - in_world_position);
    for (int i = 0; i < local_light_count(); ++i) {
        // Only the position and range first: most lights do not reach most pixels, and
        // those pixels skip the cone, the shadow lookup and the BRDF.
        const vec4 position_range = local.lights[i].position_range;
        const vec3 light_vector = position_range.xyz - in_world_position;
        const float distance = length(light_vector);
        const vec3 to_light = light_vector / max(distance, 1e-4);
        const bool in_range = distance < position_range.w && dot(normal, to_light) > 0.0;
        const float cone = in_range ? spot_cone(local.lights[i], to_light) : 0.0;
        if (cone <= 0.0) {
            if (i == int(local.counts.y)) visibility = 0.0;
            continue;
        }
        const LocalLight light = local.lights[i];
        const float shadow = local_shadow(light, in_world_position, normal, plane_normal);
        if (i == int(local.counts.y)) visibility = shadow * cone;
        const float falloff = distance_falloff(distance, position_range.w);
        color += shade_sun(base_color.rgb, normal, to_view, to_light, light.radiance.rgb * (falloff * cone * shadow),
                           draw.material.y, draw.material.z);
    }
    color += base_color.rgb * frame.ambient.rgb;
    if (frame.options.x == PENUMBRA_DEBUG_VIEW_CASCADES && cascade >= 0) color *= kCascadeTints[cascade];

    out_color = vec4(tone_map(color), 1.0);
    out_visibility = visibility;
    out_cascade = cascade >= 0 ? uint(cascade) : PENUMBRA_NO_CASCADE;
}
