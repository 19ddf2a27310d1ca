#version 460
// Moments pass: writes the moments of each caster's distance from the light (VSM, EVSM
// or MSM, per the filter's specialization constants) into one layer of the moments
// map. Alpha-masked casters discard below their cutoff, as in the depth pass.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_shared.h"

layout(std140, set = PENUMBRA_SET_FRAME, binding = PENUMBRA_BINDING_FRAME_UNIFORMS) uniform FrameBlock {
    FrameUniforms frame;
};
layout(push_constant) uniform PushBlock { DrawPushConstants draw; };
layout(set = PENUMBRA_SET_MATERIAL, binding = PENUMBRA_BINDING_BASE_COLOR_TEXTURE) uniform sampler2D base_color_texture;

#include "shadow_filter_constants.glsl"
#include "moments.glsl"

layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_moments;

void main() {
    // Reverse-Z: the occluder's distance from the light is 1 - depth (larger = farther).
    const float distance = 1.0 - gl_FragCoord.z;
    const float distance_dx = dFdx(distance);  // before the discard: uniform control flow
    const float distance_dy = dFdy(distance);
    if (draw.flags.z == PENUMBRA_ALPHA_MASK) {
        float alpha = draw.base_color.a;
        if (draw.flags.y != 0u) alpha *= texture(base_color_texture, in_uv).a;
        if (alpha < draw.material.x) discard;
    }
    out_moments = encode_moments(kFilterMode, distance, distance_dx, distance_dy, frame.moment_params.yz, kMsmQuantized);
}
