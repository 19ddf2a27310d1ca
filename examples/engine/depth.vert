#version 460
// The engine example's depth-only pass for the resolved view: positions through the
// application's own (jittered, reverse-Z) view-projection; nothing but depth is written.
layout(push_constant) uniform Push {
    mat4 view_projection;
    mat4 model;
};

layout(location = 0) in vec3 in_position;

void main() {
    gl_Position = view_projection * (model * vec4(in_position, 1.0));
}
