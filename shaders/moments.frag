#version 460
// Moments pass: writes the moments of each caster's distance from the light (VSM, EVSM
// or MSM, per the filter's specialization constants) into one layer of the moments map.
// The PENUMBRA_MASKED variant alpha-tests as the depth pass's masked casters do.
#extension GL_GOOGLE_include_directive : require
#include "penumbra_internal.h"

layout(std140, set = PENUMBRA_SET_CASTER_FRAME, binding = PENUMBRA_BINDING_CASTER_SHADOW_UNIFORMS) uniform ShadowBlock {
    PenumbraShadowUniforms shadow;
};
layout(push_constant) uniform PushBlock { CasterPushConstants caster; };

#include "penumbra/glsl/filter_constants.glsl"
#include "penumbra/glsl/moments.glsl"

#ifdef PENUMBRA_MASKED
layout(set = PENUMBRA_SET_ALPHA_MASK, binding = PENUMBRA_BINDING_ALPHA_MASK) uniform sampler2D alpha_mask;
layout(location = 0) in vec2 in_uv;
#endif
layout(location = 0) out vec4 out_moments;

void main() {
    // Reverse-Z: the occluder's distance from the light is 1 - depth (larger = farther).
    const float distance = 1.0 - gl_FragCoord.z;
    const float distance_dx = dFdx(distance);  // before the discard: uniform control flow
    const float distance_dy = dFdy(distance);
#ifdef PENUMBRA_MASKED
    if (caster.alpha_scale * texture(alpha_mask, in_uv).a < caster.alpha_cutoff) discard;
#endif
    const vec2 exponents = vec2(shadow.evsm_positive_exponent, shadow.evsm_negative_exponent);
    out_moments = penumbra_encode_moments(kPenumbraFilterMode, distance, distance_dx, distance_dy, exponents,
                                          kPenumbraMsmQuantized);
}
