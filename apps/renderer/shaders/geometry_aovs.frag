#version 460
// Geometry AOVs for `penumbra compare`: the world position and the shading normal of the
// surface each pixel shows, for the ray-traced shadow reference to start its rays from.
// Drawn with lighting.vert, the lighting pass's raster state and draw order and the same
// alpha test, so it covers exactly the pixels (and surfaces) the lighting pass shades; the
// normal is the one lighting.frag passes to the shadow lookup.
#extension GL_GOOGLE_include_directive : require
#include "renderer_shared.h"

layout(push_constant) uniform PushBlock { DrawPushConstants draw; };
layout(set = RENDERER_SET_MATERIAL, binding = RENDERER_BINDING_BASE_COLOR_TEXTURE) uniform sampler2D base_color_texture;

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec4 out_world_position;  // w = 1: geometry (the clear value has w = 0)
layout(location = 1) out vec4 out_world_normal;  // w = 1: the instance receives no shadow

void main() {
    vec3 normal = normalize(in_world_normal);
    if (!gl_FrontFacing) normal = -normal;  // double-sided materials are lit from both sides

    vec4 base_color = draw.base_color;
    if (draw.flags.y != 0u) base_color *= texture(base_color_texture, in_uv);
    if (draw.flags.z == RENDERER_ALPHA_MASK && base_color.a < draw.material.x) discard;

    out_world_position = vec4(in_world_position, 1.0);
    out_world_normal = vec4(normal, draw.flags.w != 0u ? 0.0 : 1.0);
}
