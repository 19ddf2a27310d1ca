#version 460
// Forward lighting pass: world-space position and normal for shading and shadow lookup.
#extension GL_GOOGLE_include_directive : require
#include "renderer_shared.h"

layout(std140, set = RENDERER_SET_FRAME, binding = RENDERER_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};
layout(push_constant) uniform PushBlock { DrawPushConstants draw; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 out_world_position;
layout(location = 1) out vec3 out_world_normal;
layout(location = 2) out vec2 out_uv;

void main() {
    const vec4 world = draw.model * vec4(in_position, 1.0);
    out_world_position = world.xyz;
    // Inverse transpose keeps normals perpendicular under non-uniform scale.
    out_world_normal = transpose(inverse(mat3(draw.model))) * in_normal;
    out_uv = in_uv;
    gl_Position = frame.view_projection * world;
}
