#version 460
// Shadow-map depth pass: transforms casters into one cascade's clip space. With the
// per-cascade strategy the cascade comes from the push constants; with multiview one
// pass renders every layer and gl_ViewIndex selects the cascade.
#extension GL_EXT_multiview : require
#extension GL_GOOGLE_include_directive : require
#include "penumbra_shared.h"

layout(std140, set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};
layout(push_constant) uniform PushBlock { DrawPushConstants draw; };

layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;
layout(location = 0) out vec2 out_uv;

void main() {
    const uint cascade = draw.flags.x + gl_ViewIndex;
    gl_Position = frame.cascade_view_projection[cascade] * (draw.model * vec4(in_position, 1.0));
    out_uv = in_uv;
}
