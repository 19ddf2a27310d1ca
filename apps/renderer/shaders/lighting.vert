#version 460
// Forward lighting pass: world-space position and normal for shading and shadow lookup.
#extension GL_GOOGLE_include_directive : require
#include "renderer_shared.h"

layout(std140, set = RENDERER_SET_FRAME, binding = RENDERER_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};
layout(std430, set = RENDERER_SET_FRAME, binding = RENDERER_BINDING_DRAW_MODELS) readonly buffer ModelBlock {
    mat4 draw_models[];
};
layout(std430, set = RENDERER_SET_FRAME, binding = RENDERER_BINDING_INSTANCE_DRAWS) readonly buffer InstanceBlock {
    uint instance_draws[];
};

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
#ifdef RENDERER_VERTEX_COLOR
// Only the lighting pass reads it: an output no fragment shader consumes is a validation
// warning, so the other passes use the variant without it.
layout(location = 3) in vec4 in_color;  // glTF COLOR_0 (white without)
#endif

layout(location = 0) out vec3 out_world_position;
layout(location = 1) out vec3 out_world_normal;
layout(location = 2) out vec2 out_uv;
#ifdef RENDERER_VERTEX_COLOR
layout(location = 3) out vec3 out_color;
#endif

void main() {
    // gl_InstanceIndex counts from the batch's firstInstance: its slot in this frame's order.
    const mat4 model = draw_models[instance_draws[gl_InstanceIndex]];
    const vec4 world = model * vec4(in_position, 1.0);
    out_world_position = world.xyz;
    // Inverse transpose keeps normals perpendicular under non-uniform scale.
    out_world_normal = transpose(inverse(mat3(model))) * in_normal;
    out_uv = in_uv;
#ifdef RENDERER_VERTEX_COLOR
    out_color = in_color.rgb;
#endif
    gl_Position = frame.view_projection * world;
}
