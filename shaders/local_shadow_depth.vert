#version 460
// Shadow-map depth pass of spot and point lights: transforms casters into one layer's
// reverse-Z perspective clip space (a spot's cone or one face of a point light's cube).
// The layer comes from the push constants (DrawPushConstants.flags.x).
#extension GL_GOOGLE_include_directive : require
#include "penumbra_shared.h"

layout(std430, set = 0, binding = 0) readonly buffer LocalLightBlock { LocalLightUniforms local; };
layout(push_constant) uniform PushBlock { DrawPushConstants draw; };

layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;
layout(location = 0) out vec2 out_uv;

void main() {
    gl_Position = local.shadow_view_projection[draw.flags.x] * (draw.model * vec4(in_position, 1.0));
    out_uv = in_uv;
}
