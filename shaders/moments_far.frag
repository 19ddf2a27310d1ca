#version 460
// Moments pass, before the casters: a full-screen triangle at the far plane (depth 0,
// shaders/fullscreen.vert) writes the moments of distance 1 wherever no caster will, so
// an empty texel reads as "nothing in front of any receiver". Rendering them instead of
// clearing keeps the encoding in one place (penumbra/glsl/moments.glsl).
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(std140, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS) uniform ShadowBlock {
    PenumbraShadowUniforms shadow;
};

#include "penumbra/glsl/filter_constants.glsl"
#include "penumbra/glsl/moments.glsl"

layout(location = 0) out vec4 out_moments;

void main() {
    const vec2 exponents = vec2(shadow.evsm_positive_exponent, shadow.evsm_negative_exponent);
    out_moments = penumbra_encode_moments(kPenumbraFilterMode, 1.0, 0.0, 0.0, exponents, kPenumbraMsmQuantized);
}
