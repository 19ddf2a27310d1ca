#version 460
// The depth and normal pre-pass of `--resolve deferred`: the depth buffer the lighting pass
// then tests for equality, the shading normal that Penumbra's compute resolve
// (ShadowSystem::record_visibility) offsets and faces the shadow lookups with, and the
// face normal it takes the receiver's plane from (ScreenInputs::face_normals). Drawn with
// lighting.vert, the lighting pass's raster state and draw order and the same alpha test,
// so it keeps exactly the fragments the lighting pass would have kept; the normal is the
// one lighting.frag passes to the shadow lookup in the forward path.
#extension GL_GOOGLE_include_directive : require
#include "renderer_shared.h"

layout(push_constant) uniform PushBlock { DrawPushConstants draw; };
layout(set = RENDERER_SET_MATERIAL, binding = RENDERER_BINDING_BASE_COLOR_TEXTURE) uniform sampler2D base_color_texture;

layout(location = 0) in vec3 in_world_position;
layout(location = 1) in vec3 in_world_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec4 out_normal;       // world space, signed (NormalEncoding::SignedFloat)
layout(location = 1) out vec4 out_face_normal;  // the triangle's plane; 0 where it is degenerate

void main() {
    vec3 normal = normalize(in_world_normal);
    if (!gl_FrontFacing) normal = -normal;  // double-sided materials are lit from both sides
    // As penumbra_geometric_normal() in forward shading, before the discard (derivatives).
    const vec3 face = cross(dFdx(in_world_position), dFdy(in_world_position));
    const float face_length_squared = dot(face, face);

    if (draw.flags.z == RENDERER_ALPHA_MASK) {
        float alpha = draw.base_color.a;
        if (draw.flags.y != 0u) alpha *= texture(base_color_texture, in_uv).a;
        if (alpha < draw.material.x) discard;
    }
    out_normal = vec4(normal, 0.0);
    out_face_normal = vec4(face_length_squared > 1e-20 ? face * inversesqrt(face_length_squared) : vec3(0.0), 0.0);
}
