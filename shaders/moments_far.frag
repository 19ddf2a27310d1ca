#version 460
// Moments pass, before the casters: a full-screen triangle at the far plane (depth 0,
// shaders/fullscreen.vert) writes the moments of distance 1 wherever no caster will, so
// an empty texel reads as "nothing in front of any receiver". Rendering them instead of
// clearing keeps the encoding in one place (moments.glsl).
#extension GL_GOOGLE_include_directive : require
#include "penumbra_shared.h"

layout(std140, set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};

#include "shadow_filter_constants.glsl"
#include "moments.glsl"

layout(location = 0) out vec4 out_moments;

void main() { out_moments = encode_moments(kFilterMode, 1.0, 0.0, 0.0, frame.moment_params.yz, kMsmQuantized); }
