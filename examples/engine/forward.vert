#version 460
// The example's own vertex shader: world position and normal for the fragment shader.
layout(push_constant) uniform Push {
    mat4 view_projection;
    mat4 model;
};

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec3 out_world_position;
layout(location = 1) out vec3 out_world_normal;

void main() {
    const vec4 world = model * vec4(in_position, 1.0);
    out_world_position = world.xyz;
    out_world_normal = mat3(model) * in_normal;  // rigid transforms only in this example
    gl_Position = view_projection * world;
}
