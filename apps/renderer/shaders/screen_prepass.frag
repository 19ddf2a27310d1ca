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

// xy: the shading normal, zw: the triangle's plane (the shading normal where the triangle
// is degenerate), world space, octahedral (NormalEncoding::Octahedral): one 8-byte target.
layout(location = 0) out vec4 out_normals;

// Octahedral encoding (Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors"): the unit sphere onto [-1, 1]^2.
vec2 encode_octahedral(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    if (n.z >= 0.0) return n.xy;
    return (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
}

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
    const vec3 face_normal = face_length_squared > 1e-20 ? face * inversesqrt(face_length_squared) : normal;
    out_normals = vec4(encode_octahedral(normal), encode_octahedral(face_normal));
}
