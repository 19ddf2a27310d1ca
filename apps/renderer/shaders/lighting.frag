#version 460
// Forward shading of the sun (Lambert diffuse + GGX specular), spot and point lights,
// ambient and emission, with every light's shadow from Penumbra's shadow library, included here as any
// renderer would include it (penumbra/shadow.glsl, its descriptor set at set 2). Besides
// the tone-mapped colour it writes two exact outputs used by tests and tools: a light's
// visibility (R16_UNORM: the sun's, or light N's with `--aov shadow:N`) and the index of
// the cascade that shadowed the pixel (R8_UINT).
//
// Compiled twice. Forward (the default): every shadow is filtered here, once per shaded
// fragment. With RENDERER_DEFERRED_SHADOWS (`--resolve deferred`): Penumbra's compute
// resolve has filtered every light's shadow once per pixel of the depth pre-pass
// (ShadowSystem::record_visibility), and this pass, drawn with an equal depth test over
// that pre-pass, reads the pixel's slots of the visibility image instead. With
// RENDERER_CONTACT_SHADOWS (forward shading with contact shadows, or `--aov contact`) the
// pass draws over the depth pre-pass with an equal test and samples it: forward, it traces
// every light's contact shadow here (penumbra/glsl/contact.glsl), as the resolve does
// deferred; `--aov contact` writes the sun's contact term alone.
#extension GL_GOOGLE_include_directive : require
#include "renderer_shared.h"

layout(std140, set = RENDERER_SET_FRAME, binding = RENDERER_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};
layout(std430, set = RENDERER_SET_FRAME, binding = RENDERER_BINDING_LIGHTS) readonly buffer LightBlock {
    LocalLights local;
};
layout(push_constant) uniform PushBlock { DrawPushConstants draw; };
layout(set = RENDERER_SET_MATERIAL, binding = RENDERER_BINDING_BASE_COLOR_TEXTURE) uniform sampler2D base_color_texture;
layout(set = RENDERER_SET_MATERIAL, binding = RENDERER_BINDING_EMISSIVE_TEXTURE) uniform sampler2D emissive_texture;
layout(set = RENDERER_SET_MATERIAL, binding = RENDERER_BINDING_METALLIC_ROUGHNESS_TEXTURE) uniform sampler2D
    metallic_roughness_texture;
layout(set = RENDERER_SET_MATERIAL, binding = RENDERER_BINDING_OCCLUSION_TEXTURE) uniform sampler2D occlusion_texture;

#define PENUMBRA_SHADOW_SET RENDERER_SET_SHADOWS
#include "penumbra/shadow.glsl"
#include "penumbra/shadow_fragment.glsl"
#include "shading.glsl"
#include "local_lighting.glsl"

#ifdef RENDERER_DEFERRED_SHADOWS
layout(set = RENDERER_SET_SCREEN, binding = RENDERER_BINDING_SHADOW_VISIBILITY) uniform sampler2DArray shadow_visibility;

// Slot s of this pixel: layer s / 4, channel s % 4 (penumbra::VisibilityImage).
float resolved_visibility(uint slot) {
    return texelFetch(shadow_visibility, ivec3(ivec2(gl_FragCoord.xy), int(slot / 4u)), 0)[slot % 4u];
}
#endif

#ifdef RENDERER_CONTACT_SHADOWS
layout(set = RENDERER_SET_SCREEN, binding = RENDERER_BINDING_CONTACT_DEPTH) uniform sampler2D contact_depth;

PenumbraContactScreen contact_screen() {
    return PenumbraContactScreen(frame.view_projection, frame.inverse_view_projection, frame.screen.xy,
                                 frame.screen.z);
}
#endif

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec3 in_vertex_color;

layout(location = 0) out vec4 out_color;
layout(location = 1) out float out_visibility;
layout(location = 2) out uint out_cascade;

const vec3 kCascadeTints[8] = vec3[](vec3(1.0, 0.25, 0.25), vec3(0.25, 1.0, 0.25), vec3(0.3, 0.45, 1.0),
                                     vec3(1.0, 1.0, 0.25), vec3(1.0, 0.3, 1.0), vec3(0.25, 1.0, 1.0),
                                     vec3(1.0, 0.6, 0.2), vec3(0.7, 0.7, 0.7));

// The virtual shadow map's pages under this pixel (--debug virtual-pages): the level it
// samples tints it, the borders of that level's 128-texel pages are dark lines, and where
// the level it wants has no resident page (unserved: the pool is full, or the page is new
// this frame) magenta stripes mark the coarser fallback or, with none, the missing shadow.
vec3 virtual_pages_debug(vec3 color) {
    const int wanted = penumbra_select_virtual_level(in_world_position, penumbra_virtual.mark_radius_texels);
    const int sampled = penumbra_virtual_receiver_level(in_world_position);
    // Derivatives before any per-pixel branch.
    const vec2 page = penumbra_virtual_texel_of(uint(max(sampled, 0)), in_world_position) /
                      float(kPenumbraVirtualPageTexels);
    const vec2 line_width = fwidth(page);
    const bool stripe = fract((gl_FragCoord.x + gl_FragCoord.y) / 8.0) < 0.5;
    if (sampled < 0) return wanted >= 0 && stripe ? vec3(1.0, 0.0, 1.0) : color;
    color *= kCascadeTints[sampled % 8];
    const vec2 to_border = min(fract(page), 1.0 - fract(page));
    if (any(lessThan(to_border, line_width))) color *= 0.25;
    if (sampled > wanted && stripe) color = vec3(1.0, 0.0, 1.0);
    return color;
}

void main() {
    vec3 normal = normalize(in_world_normal);
    if (!gl_FrontFacing) normal = -normal;  // double-sided materials are lit from both sides
    // Before the discard and every per-pixel branch: they take screen-space derivatives.
#ifndef RENDERER_DEFERRED_SHADOWS
    const PenumbraSunReceiver receiver = penumbra_sun_receiver_fragment(in_world_position, normal);
#endif
    const vec3 plane_normal = penumbra_geometric_normal(in_world_position, normal);

    vec4 base_color = draw.base_color;
    if (draw.flags.y != 0u) base_color *= texture(base_color_texture, in_uv);
    if (draw.flags.z == RENDERER_ALPHA_MASK && base_color.a < draw.material.x) discard;
    base_color.rgb *= in_vertex_color;
    // glTF's metallic-roughness texture: roughness in G, metallic in B (white without one).
    const vec2 metal_rough = texture(metallic_roughness_texture, in_uv).bg;
    const float metallic = draw.material.z * metal_rough.x;
    const float roughness = draw.material.y * metal_rough.y;

    // An instance that does not receive shadows (scene files' receive_shadows = false) is
    // lit as if nothing were in the way; the lookups stay in uniform control flow.
    const bool receives = draw.flags.w != 0u;
    const vec3 to_view = normalize(frame.camera_position.xyz - in_world_position);
#ifdef RENDERER_DEFERRED_SHADOWS
    float visibility = receives ? resolved_visibility(0u) : 1.0;
#else
    float visibility = receives ? penumbra_sun_visibility(receiver, normal) : 1.0;
#endif
#ifdef RENDERER_CONTACT_SHADOWS
    // Traced from the visible side of the surface, as the resolve does.
    const vec3 contact_normal = dot(plane_normal, to_view) < 0.0 ? -plane_normal : plane_normal;
    const bool contact_aov = frame.visibility_light == RENDERER_VISIBILITY_CONTACT;
#ifdef RENDERER_DEFERRED_SHADOWS
    // The resolve has traced them into `visibility`: this variant serves `--aov contact`.
    const bool trace_sun = contact_aov;
#else
    const bool trace_sun = contact_aov || (receives && visibility > 0.0);  // as the resolve: where the map is lit
#endif
    const float sun_contact =
        trace_sun ? penumbra_sun_contact(contact_depth, contact_screen(), in_world_position, contact_normal,
                                         gl_FragCoord.xy)
                  : 1.0;
#ifndef RENDERER_DEFERRED_SHADOWS
    if (receives) visibility = min(visibility, sun_contact);
#endif
#endif
    vec3 color = shade_sun(base_color.rgb, normal, to_view, frame.to_sun.xyz, frame.sun_radiance.rgb * visibility,
                           roughness, metallic);
    // Spot and point lights; with `--aov shadow:N` light N's visibility (shadow, cone, range,
    // facing) replaces the sun's in the visibility target.
    for (uint i = 0u; i < frame.local_light_count; ++i) {
        // Only the position and range first: most lights do not reach most pixels, and
        // those pixels skip the cone, the shadow lookup and the BRDF.
        const vec3 light_vector = local.lights[i].position - in_world_position;
        const float distance = length(light_vector);
        const vec3 to_light = light_vector / max(distance, 1e-4);
        const bool in_range =
            distance < local.lights[i].range && penumbra_faces_light(normal, plane_normal, to_light);
        const float cone = in_range ? spot_cone(local.lights[i], to_light) : 0.0;
        if (cone <= 0.0) {
            if (int(i) == frame.visibility_light) visibility = 0.0;
            continue;
        }
        const LocalLight light = local.lights[i];
#ifdef RENDERER_DEFERRED_SHADOWS
        const float shadow = receives && light.visibility_slot != 0u ? resolved_visibility(light.visibility_slot) : 1.0;
#else
        float shadow =
            receives ? penumbra_light_shadow(light.shadow_index, in_world_position, normal, plane_normal, gl_FragCoord.xy)
                     : 1.0;
#ifdef RENDERER_CONTACT_SHADOWS
        // As the resolve: for the lights with a shadow map (a visibility slot), where lit.
        if (light.visibility_slot != 0u && shadow > 0.0) {
            shadow = min(shadow, penumbra_light_contact(light.shadow_index, contact_depth, contact_screen(),
                                                        in_world_position, contact_normal, gl_FragCoord.xy));
        }
#endif
#endif
        if (int(i) == frame.visibility_light) visibility = shadow * cone;
        const float falloff = distance_falloff(distance, light.range);
        color += shade_sun(base_color.rgb, normal, to_view, to_light, light.radiance * (falloff * cone * shadow),
                           roughness, metallic);
    }
    // glTF's occlusion texture (R) darkens the ambient term only, by its strength.
    const float occlusion = mix(1.0, texture(occlusion_texture, in_uv).r, draw.emissive.w);
    color += base_color.rgb * frame.ambient.rgb * occlusion;
    // Emission (glTF emissiveFactor x texture) is the surface's own light: no shadow.
    vec3 emission = draw.emissive.rgb;
    if (draw.flags.x != 0u) emission *= texture(emissive_texture, in_uv).rgb;
    color += emission;
#ifdef RENDERER_DEFERRED_SHADOWS
    const int cascade = penumbra_sun_map_of(in_world_position);
#else
    const int cascade = receiver.cascade;
#endif
    if (frame.debug_view == RENDERER_DEBUG_VIEW_CASCADES && cascade >= 0) color *= kCascadeTints[cascade];
    if (frame.debug_view == RENDERER_DEBUG_VIEW_VIRTUAL_PAGES && penumbra_sun_is_virtual()) {
        color = virtual_pages_debug(color);
    }

#ifdef RENDERER_CONTACT_SHADOWS
    if (contact_aov) visibility = sun_contact;
#endif

    out_color = vec4(tone_map(color), 1.0);
    // The debug view's marks are exact colours, whatever the tone mapping does.
    if (frame.debug_view == RENDERER_DEBUG_VIEW_VIRTUAL_PAGES && color == vec3(1.0, 0.0, 1.0)) {
        out_color = vec4(1.0, 0.0, 1.0, 1.0);
    }
    out_visibility = visibility;
    out_cascade = cascade >= 0 ? uint(cascade) : RENDERER_NO_CASCADE;
}
